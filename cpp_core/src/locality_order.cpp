// Breadth-first vertex order and the matching triangle order.
#include "locality_order.h"

#include <algorithm>
#include <numeric>

namespace meshik {

LocalityOrder locality_order(const int* triangles, int num_triangles, int num_vertices) {
  // Vertex neighbours through triangle edges, in compressed rows (duplicates are harmless).
  std::vector<int> start(num_vertices + 1, 0);
  for (int e = 0; e < 3 * num_triangles; ++e) start[triangles[e] + 1] += 2;
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> neighbour(start[num_vertices]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int j = 0; j < num_triangles; ++j)
    for (int q = 0; q < 3; ++q) {
      const int v = triangles[3 * j + q];
      neighbour[fill[v]++] = triangles[3 * j + (q + 1) % 3];
      neighbour[fill[v]++] = triangles[3 * j + (q + 2) % 3];
    }

  LocalityOrder order;
  order.internal_of_vertex.assign(num_vertices, -1);
  order.vertex_of_internal.reserve(num_vertices);
  std::vector<int> by_degree(num_vertices);
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(by_degree.begin(), by_degree.end(), [&](int a, int b) {
    return start[a + 1] - start[a] < start[b + 1] - start[b];
  });
  auto visit = [&](int v) {
    order.internal_of_vertex[v] = static_cast<int>(order.vertex_of_internal.size());
    order.vertex_of_internal.push_back(v);
  };
  for (int root : by_degree) {
    if (order.internal_of_vertex[root] >= 0 || start[root + 1] == start[root]) continue;
    size_t head = order.vertex_of_internal.size();
    visit(root);
    for (; head < order.vertex_of_internal.size(); ++head) {
      const int v = order.vertex_of_internal[head];
      for (int s = start[v]; s < start[v + 1]; ++s)
        if (order.internal_of_vertex[neighbour[s]] < 0) visit(neighbour[s]);
    }
  }
  for (int v = 0; v < num_vertices; ++v)
    if (order.internal_of_vertex[v] < 0) visit(v);  // used by no triangle

  std::vector<int> smallest(num_triangles);
  for (int j = 0; j < num_triangles; ++j)
    smallest[j] = std::min({order.internal_of_vertex[triangles[3 * j]],
                            order.internal_of_vertex[triangles[3 * j + 1]],
                            order.internal_of_vertex[triangles[3 * j + 2]]});
  order.triangle_order.resize(num_triangles);
  std::iota(order.triangle_order.begin(), order.triangle_order.end(), 0);
  std::stable_sort(order.triangle_order.begin(), order.triangle_order.end(),
                   [&](int a, int b) { return smallest[a] < smallest[b]; });
  return order;
}

}  // namespace meshik
