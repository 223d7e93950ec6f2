// The adjacency graph of a symmetric matrix and its view under a symmetric permutation.
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"
#include "sparse/pattern.h"

namespace meshik::sparse {

// Returns the adjacency of the symmetric matrix whose lower triangle is `a` (entries above the
// diagonal ignored): column v lists the u != v with A(u, v) != 0, increasing.
Pattern adjacency_graph(const CscMatrix& a);

// The adjacency of P A P^T seen through the graph of A, without a copy: node k of the view is
// node perm[k] of `graph`, its neighbours renamed by `inverse` (inverse[perm[k]] = k). perm may
// cover only some of graph's nodes (then A is the matrix of the subgraph they induce): inverse
// labels the others with a number past the view's last node.
struct PermutedView {
  const Pattern& graph;
  const std::vector<int>& perm;
  const std::vector<int>& inverse;

  int size() const { return static_cast<int>(perm.size()); }
  // Calls visit(label[u]) for each neighbour u (numbered as in `graph`) of node k of the view,
  // in no particular order; label: one entry per node of `graph`. Asks the cache for node
  // k + kAhead's list meanwhile: the lists lie in A's order, not the view's, and a pass over the
  // view otherwise waits for each one.
  template <class Visit>
  void for_each_neighbour(int k, const std::vector<int>& label, Visit&& visit) const {
    constexpr int kAhead = 8;
    if (k + kAhead < size()) __builtin_prefetch(graph.row_index.data() + graph.col_start[perm[k + kAhead]]);
    const int v = perm[k];
    const int end = graph.col_start[v + 1];
    for (int p = graph.col_start[v]; p < end; ++p) visit(label[graph.row_index[p]]);
  }
  // Calls visit(i) for each neighbour i of node k of the view, in no particular order.
  template <class Visit>
  void for_each_neighbour(int k, Visit&& visit) const {
    for_each_neighbour(k, inverse, visit);
  }
};

}  // namespace meshik::sparse
