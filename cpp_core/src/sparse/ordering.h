// Fill-reducing ordering of a symmetric matrix: simplicial nodes (their neighbours already
// form a clique, so eliminating them first creates no fill: the 4th-vertex unknowns of
// MeshIK's kept form are such nodes) and approximate minimum degree (SuiteSparse AMD).
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// graph: adjacency of a symmetric n by n matrix (no diagonal, lists sorted).
// Returns the nodes of degree <= max_degree whose neighbours are pairwise
// adjacent, increasing.
std::vector<int> simplicial_nodes(const Pattern& graph, int max_degree);

// graph: as above. Returns AMD's permutation of it, n entries: perm[k] is the node
// eliminated k-th.
std::vector<int> minimum_degree_ordering(const Pattern& graph);

// perm: a permutation of 0..n-1. Returns its inverse (inverse[perm[k]] = k).
std::vector<int> invert_permutation(const std::vector<int>& perm);

}  // namespace meshik::sparse
