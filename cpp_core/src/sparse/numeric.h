// Multifrontal supernodal numeric factorization A = L L^T.
#pragma once

#include <vector>

#include "sparse/pattern.h"
#include "sparse/symbolic.h"

namespace meshik::sparse {

// The permuted matrix's lower triangle with its values gathered from the caller's array.
struct LowerValues {
  const Pattern* pattern;  // column j: rows i >= j of P A P^T
  const int* source;       // nnz(pattern): index of each entry's value in `values`
  const double* values;    // the caller's CscMatrix::values
};

// Factorizes into `values` (sized symbolic.value_start.back()), supernode by supernode in
// order: each supernode's block gathers A's columns and its children's update matrices, is
// factored densely, and leaves its own update matrix on a stack for its parent.
// original_column[k] names pivot k in the error. Throws NotPositiveDefinite.
void factorize_supernodal(const SymbolicFactor& symbolic, const LowerValues& a,
                          const std::vector<int>& original_column, std::vector<double>& values);

}  // namespace meshik::sparse
