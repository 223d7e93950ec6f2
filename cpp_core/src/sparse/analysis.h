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
  // a postorder of the elimination tree of its fill-reducing order.
  std::vector<int> perm;
  PermutedLower lower;      // lower triangle of P A P^T, with sources into A's values
  SimplicialPrefix prefix;  // its first columns
  SymbolicFactor symbolic;  // the supernodal structure of the remaining columns
  long long factor_nonzeros = 0;  // nnz(L), diagonal included, explicit zeros not counted
};

// a: a validated lower triangle (see check_lower_input). Returns its elimination order, n
// entries: its simplicial nodes, then approximate minimum degree on the others.
std::vector<int> fill_reducing_order(const CscMatrix& a);

// a: a validated lower triangle. Returns its analysis, ordered by fill_reducing_order(a).
Analysis analyze_pattern(const CscMatrix& a);

// As above with the non-simplicial nodes eliminated in their order in `order` (a validated
// permutation of a's n columns), e.g. a larger matrix's fill_reducing_order restricted to a's
// columns: no minimum-degree ordering is run.
Analysis analyze_pattern(const CscMatrix& a, const std::vector<int>& order);

}  // namespace meshik::sparse
