// The adjacency graph of a symmetric matrix and its view under a symmetric permutation.
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"
#include "sparse/pattern.h"

namespace meshik::sparse {

// Returns the adjacency of the symmetric matrix whose lower triangle is `a` (entries above the
// diagonal ignored): column v lists the u != v with A(u, v) != 0, increasing.
Pattern adjacency_graph(const CscMatrix& a);

// graph: an adjacency graph (n nodes); perm: n entries, perm[k] is the node that becomes k;
// inverse: its inverse. Returns the adjacency of P A P^T: column k lists the neighbours of
// perm[k] renamed by `inverse` (in no particular order).
Pattern permuted_graph(const Pattern& graph, const std::vector<int>& perm, const std::vector<int>& inverse);

// graph: an adjacency graph; kept: the nodes to keep, increasing; local[v]: v's index in
// `kept`, or -1. Returns the subgraph induced by `kept` (node kept[t] becomes t; lists stay
// sorted).
Pattern induced_subgraph(const Pattern& graph, const std::vector<int>& kept, const std::vector<int>& local);

}  // namespace meshik::sparse
