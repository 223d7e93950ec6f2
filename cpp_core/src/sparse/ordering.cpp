#include "sparse/ordering.h"

#include <amd.h>

#include <algorithm>
#include <climits>
#include <memory>
#include <stdexcept>

#include "sparse/elimination_tree.h"

namespace meshik::sparse {

namespace {

// Whether u and v are adjacent (sorted adjacency lists).
bool adjacent(const Pattern& graph, int u, int v) {
  const auto begin = graph.row_index.begin() + graph.col_start[u];
  const auto end = graph.row_index.begin() + graph.col_start[u + 1];
  return std::binary_search(begin, end, v);
}

// graph: as in postordered_minimum_degree; local[v]: node v's index among the m nodes to order
// (increasing with v), or -1 to leave it out. Returns AMD's permutation of the induced subgraph
// (m entries, perm[t] the local index eliminated t-th).
// amd_2 orders a graph given in a workspace that it overwrites. amd_order builds exactly this
// input (sorted lists of the symmetric pattern, in node order) after checking and symmetrizing
// the matrix, which the graph already is, so calling amd_2 directly skips that work. The
// workspace's room beyond the lists only sets how often AMD compacts it, and compaction moves
// lists without reordering them: the order is amd_order's (nnz/5 + n of room) with fewer
// compactions (2 nnz + n of room measured 6% faster on the elephant).
std::vector<int> amd_permutation(const Pattern& graph, const std::vector<int>& local, int m) {
  const size_t nnz = graph.row_index.size();
  if (nnz + graph.n >= static_cast<size_t>(INT_MAX))
    throw std::runtime_error("SparseCholesky: matrix too large for the AMD ordering");
  const size_t room = std::min(2 * nnz + graph.n, static_cast<size_t>(INT_MAX) - 1);
  std::unique_ptr<int[]> workspace(new int[room]);
  std::vector<int> list_start(m), length(m);
  int q = 0;
  for (int v = 0; v < graph.n; ++v) {
    const int t = local[v];
    if (t < 0) continue;
    list_start[t] = q;
    for (int p = graph.col_start[v]; p < graph.col_start[v + 1]; ++p)
      if (local[graph.row_index[p]] >= 0) workspace[q++] = local[graph.row_index[p]];
    length[t] = q - list_start[t];
  }
  std::vector<int> perm(m);
  if (q == 0) {  // no edges: any order is free of fill (AMD needs at least one)
    for (int t = 0; t < m; ++t) perm[t] = t;
    return perm;
  }
  std::vector<int> inverse(m), nv(m), head(m), elen(m), degree(m), w(m);
  double control[AMD_CONTROL];
  amd_defaults(control);
  amd_2(m, list_start.data(), workspace.get(), length.data(), static_cast<int>(room), q, nv.data(),
        inverse.data(), perm.data(), head.data(), elen.data(), degree.data(), w.data(), control, nullptr);
  return perm;
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

TreeOrder postordered_minimum_degree(const Pattern& graph, const std::vector<char>& left_out) {
  std::vector<int> local(graph.n), kept;
  for (int v = 0; v < graph.n; ++v) {
    local[v] = left_out[v] ? -1 : static_cast<int>(kept.size());
    if (!left_out[v]) kept.push_back(v);
  }
  const int m = static_cast<int>(kept.size());
  const std::vector<int> amd = amd_permutation(graph, local, m);
  // AMD's order in graph numbering, left-out nodes after every pivot.
  std::vector<int> order(m), order_inverse(graph.n, m);
  for (int k = 0; k < m; ++k) {
    order[k] = kept[amd[k]];
    order_inverse[order[k]] = k;
  }
  const std::vector<int> order_parent = elimination_tree(PermutedView{graph, order, order_inverse});
  const std::vector<int> post = tree_postorder(order_parent);
  TreeOrder result;
  result.perm.resize(m);
  result.inverse.assign(graph.n, m);
  for (int k = 0; k < m; ++k) {
    result.perm[k] = order[post[k]];
    result.inverse[result.perm[k]] = k;
  }
  result.parent = relabel_tree(order_parent, post);
  return result;
}

std::vector<int> invert_permutation(const std::vector<int>& perm) {
  std::vector<int> inverse(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
  return inverse;
}

}  // namespace meshik::sparse
