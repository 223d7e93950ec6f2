// The ExampleSet's mesh phases on a team of threads: the triangle adjacency and the eliminated
// normal matrix's values are the same, bit for bit, for any number of threads, on a mesh large
// enough for every thread to get a share, non-manifold edges included.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "gradient_operator.h"
#include "mesh_topology.h"
#include "triangle_frames.h"

namespace {

// A wavy (side + 1) x (side + 1) grid of vertices, two triangles per cell, and a fin (one more
// vertex) on every 7th cell's diagonal, so that those edges have three triangles.
struct FinnedGrid {
  std::vector<double> vertices;  // #V x 3
  std::vector<int> triangles;    // #F x 3
  int num_vertices() const { return static_cast<int>(vertices.size() / 3); }
  int num_triangles() const { return static_cast<int>(triangles.size() / 3); }
};

FinnedGrid finned_grid(int side) {
  FinnedGrid grid;
  for (int i = 0; i <= side; ++i)
    for (int j = 0; j <= side; ++j)
      grid.vertices.insert(grid.vertices.end(), {1.0 * i, 1.0 * j, 0.3 * std::sin(0.7 * i) * std::cos(0.4 * j)});
  const auto vertex = [side](int i, int j) { return i * (side + 1) + j; };
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const int a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      grid.triangles.insert(grid.triangles.end(), {a, b, c, a, c, d});
      if ((i * side + j) % 7 != 0) continue;
      const int fin = grid.num_vertices();
      grid.vertices.insert(grid.vertices.end(), {i + 0.5, j + 0.5, 1.0});
      grid.triangles.insert(grid.triangles.end(), {a, c, fin});
    }
  return grid;
}

TEST(TeamPhases, TriangleAdjacencyIsTheSameOnAnyTeam) {
  const FinnedGrid grid = finned_grid(200);
  ASSERT_GT(grid.num_triangles(), 5 * 16384);  // every thread of a team of 5 gets triangles
  const meshik::TriangleAdjacency one =
      meshik::triangle_adjacency(grid.triangles.data(), grid.num_triangles(), grid.num_vertices());
  // A fin's diagonal joins three triangles: each of them has the other two as neighbours there.
  // Cell (0, 0)'s first triangle: the other half and the fin across its diagonal, and the next
  // cell's triangle across its edge (1, 0)-(1, 1).
  EXPECT_EQ(one.start[1] - one.start[0], 3);
  for (int team : {2, 3, 5}) {
    const meshik::TriangleAdjacency many =
        meshik::triangle_adjacency(grid.triangles.data(), grid.num_triangles(), grid.num_vertices(), team);
    EXPECT_EQ(many.start, one.start) << team << " threads";
    EXPECT_EQ(many.neighbour, one.neighbour) << team << " threads";
  }
}

TEST(TeamPhases, EliminatedNormalMatrixIsTheSameBitsOnAnyTeam) {
  const FinnedGrid grid = finned_grid(120);
  const int n = grid.num_vertices(), m = grid.num_triangles();
  const meshik::TriangleFrames frames = meshik::compute_triangle_frames(grid.vertices.data(), grid.triangles.data(), m);
  std::vector<int> row_of_vertex(n);
  for (int v = 0; v < n; ++v) row_of_vertex[v] = v;
  const meshik::CscMatrix pattern = meshik::eliminated_lower_pattern(grid.triangles.data(), m, row_of_vertex, n);
  const std::vector<double> one =
      meshik::eliminated_lower_values(frames, grid.triangles.data(), row_of_vertex, pattern);
  ASSERT_EQ(one.size(), pattern.row_index.size());
  // A diagonal entry sums the Gram terms of every triangle around its vertex: positive.
  for (int c = 0; c < n; ++c) EXPECT_GT(one[pattern.col_start[c]], 0.0) << "vertex " << c;
  for (int team : {2, 3, 7, 64}) {
    const std::vector<double> many =
        meshik::eliminated_lower_values(frames, grid.triangles.data(), row_of_vertex, pattern, team);
    ASSERT_EQ(many.size(), one.size());
    EXPECT_EQ(std::memcmp(many.data(), one.data(), one.size() * sizeof(double)), 0) << team << " threads";
  }
}

}  // namespace
