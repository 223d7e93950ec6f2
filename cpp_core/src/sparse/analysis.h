// Symbolic analysis of a symmetric matrix's pattern: ordering, simplicial prefix and
// supernodal structure of the Cholesky factor, everything the numeric factorization and the
// solves need besides the values.
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"
#include "sparse/permuted_matrix.h"
#include "sparse/simplicial_prefix.h"
#include "sparse/symbolic.h"

namespace meshik::sparse {

struct Analysis {
  // perm[k]: original index of pivot k. First the simplicial nodes (no fill), then the rest in
  // a postorder of the elimination tree of its minimum-degree order.
  std::vector<int> perm;
  PermutedLower lower;      // lower triangle of P A P^T, with sources into A's values
  SimplicialPrefix prefix;  // its first columns
  SymbolicFactor symbolic;  // the supernodal structure of the remaining columns
  long long factor_nonzeros = 0;  // nnz(L), diagonal included, explicit zeros not counted
};

// a: a validated lower triangle (see check_lower_input). Returns its analysis.
Analysis analyze_pattern(const CscMatrix& a);

}  // namespace meshik::sparse
