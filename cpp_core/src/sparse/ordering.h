// Fill-reducing ordering of a symmetric matrix (approximate minimum degree, SuiteSparse AMD).
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// lower: the lower triangle (diagonal included or not) of a symmetric n by n pattern, rows
// sorted and unique in every column.
// Returns perm, n entries: perm[k] is the original index of the k-th pivot.
std::vector<int> minimum_degree_ordering(const Pattern& lower);

// perm: a permutation of 0..n-1. Returns its inverse (inverse[perm[k]] = k).
std::vector<int> invert_permutation(const std::vector<int>& perm);

}  // namespace meshik::sparse
