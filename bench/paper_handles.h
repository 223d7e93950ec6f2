// Handle vertices spread over a mesh by farthest-point sampling, for the paper-table benchmark
// and the solver's tests.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

namespace meshik_bench {

// vertices: #V by 3 row-major positions; count: how many handles (<= #V); first: the first one.
// Returns count distinct vertex indices, each the vertex farthest (Euclidean) from those before.
inline std::vector<int> farthest_point_handles(const std::vector<double>& vertices, int count,
                                               int first = 0) {
  const int n = static_cast<int>(vertices.size() / 3);
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  std::vector<int> handles;
  int next = first;
  while (static_cast<int>(handles.size()) < count) {
    handles.push_back(next);
    distance[next] = 0.0;
    const double* p = &vertices[3 * static_cast<size_t>(next)];
    int farthest = next;
    for (int v = 0; v < n; ++v) {
      const double* q = &vertices[3 * static_cast<size_t>(v)];
      const double d = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2]);
      distance[v] = std::min(distance[v], d);
      if (distance[v] > distance[farthest]) farthest = v;
    }
    next = farthest;
  }
  return handles;
}

// The rows `indices` of a #V by 3 row-major array, as a #indices by 3 row-major array.
inline std::vector<double> gather_rows(const std::vector<double>& vertices,
                                       const std::vector<int>& indices) {
  std::vector<double> rows;
  rows.reserve(3 * indices.size());
  for (int v : indices)
    rows.insert(rows.end(), vertices.begin() + 3 * static_cast<size_t>(v),
                vertices.begin() + 3 * static_cast<size_t>(v) + 3);
  return rows;
}

}  // namespace meshik_bench
