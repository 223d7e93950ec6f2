// The locality order: a permutation of the vertices and of the triangles, and the vertex
// components it finds (its breadth-first runs) against a search over the triangles themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "locality_order.h"

namespace {

// Three grids of (side x side) cells in a random vertex numbering, two of them joined at one
// vertex only (one component), and 5 vertices of no triangle among them; the triangles shuffled.
struct ScatteredMesh {
  std::vector<int> triangles;
  int num_vertices = 0;
};

ScatteredMesh scattered_mesh(int side) {
  ScatteredMesh mesh;
  const int grid_vertices = (side + 1) * (side + 1);
  const int unused = 5;
  mesh.num_vertices = 3 * grid_vertices + unused;
  std::mt19937 random(11);
  std::vector<int> number(mesh.num_vertices);
  std::iota(number.begin(), number.end(), 0);
  std::shuffle(number.begin(), number.end(), random);
  for (int grid = 0; grid < 3; ++grid)
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        const int v = grid * grid_vertices + r * (side + 1) + c;
        const int corners[6] = {v, v + 1, v + side + 2, v, v + side + 2, v + side + 1};
        for (int corner : corners) {
          // The second grid's last vertex is the first grid's first: those two grids touch.
          const int joined = grid == 1 && corner == 2 * grid_vertices - 1 ? 0 : corner;
          mesh.triangles.push_back(number[joined]);
        }
      }
  std::vector<int> order(mesh.triangles.size() / 3);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), random);
  std::vector<int> shuffled;
  for (int j : order)
    shuffled.insert(shuffled.end(), mesh.triangles.begin() + 3 * j, mesh.triangles.begin() + 3 * j + 3);
  mesh.triangles = shuffled;
  return mesh;
}

TEST(LocalityOrder, ComponentsAreTheVerticesLinkedByTrianglesNumberedByLeastInternalVertex) {
  const ScatteredMesh mesh = scattered_mesh(9);
  const int m = static_cast<int>(mesh.triangles.size() / 3);
  const meshik::LocalityOrder order = meshik::locality_order(mesh.triangles.data(), m, mesh.num_vertices);
  // Permutations, inverse to each other.
  for (int v = 0; v < mesh.num_vertices; ++v) EXPECT_EQ(order.internal_of_vertex[order.vertex_of_internal[v]], v);
  std::vector<int> sorted = order.triangle_order;
  std::sort(sorted.begin(), sorted.end());
  for (int j = 0; j < m; ++j) EXPECT_EQ(sorted[j], j);
  // The reference: a search over the triangles (in the internal numbering) from each vertex not
  // yet reached, in increasing internal order.
  std::vector<std::vector<int>> triangles_of(mesh.num_vertices);
  for (int j = 0; j < m; ++j)
    for (int q = 0; q < 3; ++q) triangles_of[order.internal_of_vertex[mesh.triangles[3 * j + q]]].push_back(j);
  std::vector<int> expected(mesh.num_vertices, -1);
  int count = 0;
  for (int seed = 0; seed < mesh.num_vertices; ++seed) {
    if (expected[seed] >= 0 || triangles_of[seed].empty()) continue;
    std::vector<int> stack = {seed};
    expected[seed] = count;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int j : triangles_of[v])
        for (int q = 0; q < 3; ++q) {
          const int w = order.internal_of_vertex[mesh.triangles[3 * j + q]];
          if (expected[w] < 0) {
            expected[w] = count;
            stack.push_back(w);
          }
        }
    }
    ++count;
  }
  EXPECT_EQ(count, 2);
  EXPECT_EQ(order.components.count, count);
  EXPECT_EQ(order.components.component_of_vertex, expected);
  // The vertices of no triangle (the 5 spare ones and the second grid's replaced corner) come last.
  const int in_triangles = mesh.num_vertices - 6;
  for (int v = 0; v < mesh.num_vertices; ++v) EXPECT_EQ(order.components.component_of_vertex[v] < 0, v >= in_triangles);
}

}  // namespace
