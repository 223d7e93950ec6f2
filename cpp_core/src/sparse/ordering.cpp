#include "sparse/ordering.h"

#include <amd.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace meshik::sparse {

namespace {

// Whether u and v are adjacent (sorted adjacency lists).
bool adjacent(const Pattern& graph, int u, int v) {
  const auto begin = graph.row_index.begin() + graph.col_start[u];
  const auto end = graph.row_index.begin() + graph.col_start[u + 1];
  return std::binary_search(begin, end, v);
}

}  // namespace

std::vector<int> simplicial_nodes(const Pattern& graph, int max_degree) {
  std::vector<int> nodes;
  for (int v = 0; v < graph.n; ++v) {
    const int begin = graph.col_start[v], end = graph.col_start[v + 1];
    if (end - begin > max_degree) continue;
    bool clique = true;
    for (int p = begin; p < end && clique; ++p)
      for (int q = p + 1; q < end && clique; ++q) clique = adjacent(graph, graph.row_index[p], graph.row_index[q]);
    if (clique) nodes.push_back(v);
  }
  return nodes;
}

std::vector<int> minimum_degree_ordering(const Pattern& graph) {
  std::vector<int> perm(graph.n);
  if (graph.row_index.empty()) {  // no edges: any order is free of fill (AMD rejects it)
    for (int v = 0; v < graph.n; ++v) perm[v] = v;
    return perm;
  }
  double control[AMD_CONTROL];
  amd_defaults(control);
  const int status = amd_order(graph.n, graph.col_start.data(), graph.row_index.data(), perm.data(), control,
                               nullptr);
  if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED)
    throw std::runtime_error("SparseCholesky: AMD ordering failed with status " + std::to_string(status));
  return perm;
}

std::vector<int> invert_permutation(const std::vector<int>& perm) {
  std::vector<int> inverse(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
  return inverse;
}

}  // namespace meshik::sparse
