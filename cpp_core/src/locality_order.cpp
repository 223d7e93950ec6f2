// Breadth-first vertex order and the matching triangle order.
#include "locality_order.h"

#include <algorithm>
#include <numeric>

namespace meshik {

namespace {

// The indices 0..key.size()-1 sorted by key (each in [0, num_keys)), ties in index order: a
// counting sort (std::stable_sort's result, in linear time).
std::vector<int> stable_order_by_key(const std::vector<int>& key, int num_keys) {
  std::vector<int> start(num_keys + 1, 0);
  for (int k : key) ++start[k + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> order(key.size());
  for (size_t i = 0; i < key.size(); ++i) order[start[key[i]]++] = static_cast<int>(i);
  return order;
}

}  // namespace

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
  std::vector<int> degree(num_vertices);
  for (int v = 0; v < num_vertices; ++v) degree[v] = start[v + 1] - start[v];
  const int max_degree = num_vertices > 0 ? *std::max_element(degree.begin(), degree.end()) : 0;
  const std::vector<int> by_degree = stable_order_by_key(degree, max_degree + 1);
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
  order.triangle_order = stable_order_by_key(smallest, num_vertices);
  return order;
}

}  // namespace meshik
