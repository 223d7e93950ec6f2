// Fill-reducing ordering of a symmetric matrix: simplicial nodes (their neighbours already
// form a clique, so eliminating them first creates no fill: the 4th-vertex unknowns of
// MeshIK's kept form are such nodes) and approximate minimum degree (SuiteSparse AMD, its ties
// broken all over the graph), postordered along its elimination tree.
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// graph: adjacency of a symmetric n by n matrix (no diagonal, lists sorted).
// Returns the nodes of degree <= max_degree whose neighbours are pairwise
// adjacent, increasing.
std::vector<int> simplicial_nodes(const Pattern& graph, int max_degree);

// Consecutive nodes of a breadth-first order that spread_breadth_first keeps together.
constexpr int kSpreadChunk = 256;

// A symmetric permutation of some of a graph's nodes and the elimination tree of the permuted
// matrix.
struct TreeOrder {
  std::vector<int> perm;     // m: perm[k] is the node (graph numbering) eliminated k-th
  std::vector<int> inverse;  // graph.n: inverse[perm[k]] = k, and m for a node left out
  std::vector<int> parent;   // m: elimination tree of P A P^T (parent[k] > k, or -1 for a root)
};

// graph: as above; left_out: graph.n flags, nonzero for the nodes not to order. Returns AMD's
// order of the subgraph induced by the other m nodes (the one amd_order gives for it renumbered
// in chunks of a breadth-first order spread over the graph: ordering.cpp) followed by
// a depth-first postorder of its elimination tree (children in increasing order), so that every
// subtree is a run of consecutive columns. Fill and the tree's shape are AMD's.
TreeOrder postordered_minimum_degree(const Pattern& graph, const std::vector<char>& left_out);

// start, neighbour: a graph's lists as for breadth_first_order. Returns its n nodes renumbered for
// AMD's tie-breaks (ordering.cpp): chunks of kSpreadChunk consecutive nodes of its breadth-first
// order, the chunks in the bit-reversed order of their index; order[t] is the node numbered t.
std::vector<int> spread_breadth_first(const std::vector<int>& start, const std::vector<int>& neighbour);

// perm: a permutation of 0..n-1. Returns its inverse (inverse[perm[k]] = k).
std::vector<int> invert_permutation(const std::vector<int>& perm);

}  // namespace meshik::sparse
