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

// The subgraph induced by `kept` (node kept[t] becomes t); local[v] is v's new index or -1.
Pattern induced_subgraph(const Pattern& graph, const std::vector<int>& kept, const std::vector<int>& local) {
  Pattern sub;
  sub.n = static_cast<int>(kept.size());
  sub.col_start.reserve(sub.n + 1);
  sub.col_start.push_back(0);
  sub.row_index.reserve(graph.row_index.size());
  for (int v : kept) {
    for (int p = graph.col_start[v]; p < graph.col_start[v + 1]; ++p)
      if (local[graph.row_index[p]] >= 0) sub.row_index.push_back(local[graph.row_index[p]]);
    sub.col_start.push_back(static_cast<int>(sub.row_index.size()));
  }
  return sub;
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
  if (graph.n == 0) return perm;
  double control[AMD_CONTROL];
  amd_defaults(control);
  const int status = amd_order(graph.n, graph.col_start.data(), graph.row_index.data(), perm.data(), control,
                               nullptr);
  if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED)
    throw std::runtime_error("SparseCholesky: AMD ordering failed with status " + std::to_string(status));
  return perm;
}

std::vector<int> fill_reducing_ordering(const Pattern& graph) {
  // Degree 4 covers a 4th-vertex unknown (3 neighbours) with room for one more; larger
  // cliques are rare in meshes and cost more to test.
  constexpr int kMaxSimplicialDegree = 4;
  std::vector<int> perm = simplicial_nodes(graph, kMaxSimplicialDegree);
  if (perm.empty()) return minimum_degree_ordering(graph);
  std::vector<char> simplicial(graph.n, 0);
  for (int v : perm) simplicial[v] = 1;
  std::vector<int> local(graph.n, -1), kept;
  for (int v = 0; v < graph.n; ++v)
    if (!simplicial[v]) {
      local[v] = static_cast<int>(kept.size());
      kept.push_back(v);
    }
  for (int t : minimum_degree_ordering(induced_subgraph(graph, kept, local))) perm.push_back(kept[t]);
  return perm;
}

std::vector<int> invert_permutation(const std::vector<int>& perm) {
  std::vector<int> inverse(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
  return inverse;
}

}  // namespace meshik::sparse
