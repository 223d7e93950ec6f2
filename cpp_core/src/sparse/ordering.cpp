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

// graph: as in postordered_minimum_degree. Returns AMD's permutation (n entries, perm[k] the node
// eliminated k-th) and writes its inverse to `inverse` (n entries).
// amd_2 orders a graph given in a workspace that it overwrites. amd_order builds exactly this
// input (sorted lists of the symmetric pattern, in node order) after checking and symmetrizing
// the matrix, which the graph already is, so calling amd_2 directly skips that work. The
// workspace's room beyond the lists only sets how often AMD compacts it, and compaction moves
// lists without reordering them: the order is amd_order's (nnz/5 + n of room) with fewer
// compactions (2 nnz + n of room measured 6% faster on the elephant).
std::vector<int> amd_permutation(const Pattern& graph, std::vector<int>& inverse) {
  const int n = graph.n;
  std::vector<int> perm(n);
  inverse.resize(n);
  const size_t nnz = graph.row_index.size();
  if (nnz == 0) {  // no edges: any order is free of fill (AMD needs at least one)
    for (int v = 0; v < n; ++v) perm[v] = inverse[v] = v;
    return perm;
  }
  if (nnz + n >= static_cast<size_t>(INT_MAX))
    throw std::runtime_error("SparseCholesky: matrix too large for the AMD ordering");
  const size_t room = std::min(2 * nnz + n, static_cast<size_t>(INT_MAX) - 1);
  std::unique_ptr<int[]> workspace(new int[room]);
  std::copy(graph.row_index.begin(), graph.row_index.end(), workspace.get());
  std::vector<int> list_start(graph.col_start.begin(), graph.col_start.end() - 1), length(n);
  for (int v = 0; v < n; ++v) length[v] = graph.col_start[v + 1] - graph.col_start[v];
  std::vector<int> nv(n), head(n), elen(n), degree(n), w(n);
  double control[AMD_CONTROL];
  amd_defaults(control);
  amd_2(n, list_start.data(), workspace.get(), length.data(), static_cast<int>(room), static_cast<int>(nnz),
        nv.data(), inverse.data(), perm.data(), head.data(), elen.data(), degree.data(), w.data(), control,
        nullptr);
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

TreeOrder postordered_minimum_degree(const Pattern& graph) {
  std::vector<int> order_inverse;
  const std::vector<int> order = amd_permutation(graph, order_inverse);
  const std::vector<int> order_parent = elimination_tree(PermutedView{graph, order, order_inverse});
  const std::vector<int> post = tree_postorder(order_parent);
  TreeOrder result;
  result.perm.resize(graph.n);
  for (int k = 0; k < graph.n; ++k) result.perm[k] = order[post[k]];
  result.inverse = invert_permutation(result.perm);
  result.parent = relabel_tree(order_parent, post);
  return result;
}

std::vector<int> invert_permutation(const std::vector<int>& perm) {
  std::vector<int> inverse(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
  return inverse;
}

}  // namespace meshik::sparse
