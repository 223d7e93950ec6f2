// Triangle edge adjacency and triangle components.
#include "mesh_topology.h"

#include <algorithm>
#include <cstddef>
#include <exception>
#include <numeric>

namespace meshik {

namespace {

// triangle_adjacency gives each thread of its team at least this many triangles (fewer threads on
// a smaller mesh).
constexpr int kTrianglesPerThread = 16384;

}  // namespace

TriangleAdjacency triangle_adjacency(const int* triangles, int num_triangles, int num_vertices, int team) {
  // The triangles' edges by their lower vertex, in compressed rows: (higher vertex, triangle),
  // triangles ascending. A triangle with distinct corners holds an edge {a, b} exactly when it
  // holds both a and b.
  std::vector<int> start(num_vertices + 1, 0);
  for (int j = 0; j < num_triangles; ++j)
    for (int q = 0; q < 3; ++q) ++start[std::min(triangles[3 * j + q], triangles[3 * j + (q + 1) % 3]) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> edges(2 * static_cast<std::size_t>(start[num_vertices]));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int j = 0; j < num_triangles; ++j)
      for (int q = 0; q < 3; ++q) {
        const int a = triangles[3 * j + q], b = triangles[3 * j + (q + 1) % 3];
        const int at = fill[std::min(a, b)]++;
        edges[2 * at] = std::max(a, b);
        edges[2 * at + 1] = j;
      }
  }
  // Each thread lists the neighbours of a contiguous range of triangles (start[j + 1]: the length of
  // its range's list up to triangle j); the ranges' lists are then joined in order. (An allocation
  // failure is rethrown after the loop.)
  TriangleAdjacency adjacency;
  adjacency.start.assign(num_triangles + 1, 0);
  const int parts = std::max(1, std::min(team, num_triangles / kTrianglesPerThread));
  const auto first_of_part = [num_triangles, parts](int part) {
    return static_cast<int>(static_cast<long long>(num_triangles) * part / parts);
  };
  std::vector<std::vector<int>> part_neighbours(parts);
  std::vector<std::exception_ptr> part_failure(parts);
#pragma omp parallel for schedule(static, 1) num_threads(parts) if (parts > 1)
  for (int part = 0; part < parts; ++part) {
    const int first = first_of_part(part), last = first_of_part(part + 1);
    std::vector<int>& neighbours = part_neighbours[part];
    try {
      neighbours.reserve(3 * static_cast<std::size_t>(last - first));
      for (int j = first; j < last; ++j) {
        for (int q = 0; q < 3; ++q) {
          const int a = triangles[3 * j + q], b = triangles[3 * j + (q + 1) % 3];
          const int low = std::min(a, b), high = std::max(a, b);
          // The other triangles on the edge (a, b), ascending.
          for (int e = start[low]; e < start[low + 1]; ++e)
            if (edges[2 * e] == high && edges[2 * e + 1] != j) neighbours.push_back(edges[2 * e + 1]);
        }
        adjacency.start[j + 1] = static_cast<int>(neighbours.size());
      }
    } catch (...) {
      part_failure[part] = std::current_exception();
    }
  }
  for (const std::exception_ptr& failure : part_failure)
    if (failure) std::rethrow_exception(failure);
  if (parts == 1) {
    adjacency.neighbour = std::move(part_neighbours[0]);
    return adjacency;
  }
  std::vector<int> offset(parts + 1, 0);  // where each range's list goes
  for (int part = 0; part < parts; ++part)
    offset[part + 1] = offset[part] + static_cast<int>(part_neighbours[part].size());
  adjacency.neighbour.resize(offset[parts]);
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int part = 0; part < parts; ++part) {
    for (int j = first_of_part(part); j < first_of_part(part + 1); ++j) adjacency.start[j + 1] += offset[part];
    std::copy(part_neighbours[part].begin(), part_neighbours[part].end(), adjacency.neighbour.begin() + offset[part]);
  }
  return adjacency;
}

TriangleComponents triangle_components(const TriangleAdjacency& adjacency) {
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  TriangleComponents components;
  components.component_of.assign(m, -1);
  std::vector<int> queue;
  queue.reserve(m);
  for (int start = 0; start < m; ++start) {
    if (components.component_of[start] >= 0) continue;
    const int id = components.count++;
    components.component_of[start] = id;
    queue.assign(1, start);
    for (std::size_t head = 0; head < queue.size(); ++head)
      for (int s = adjacency.start[queue[head]]; s < adjacency.start[queue[head] + 1]; ++s) {
        const int n = adjacency.neighbour[s];
        if (components.component_of[n] < 0) {
          components.component_of[n] = id;
          queue.push_back(n);
        }
      }
  }
  return components;
}

}  // namespace meshik
