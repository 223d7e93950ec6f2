// The lower triangle of the symmetric permutation P A P^T, with a map back to A's values.
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"
#include "sparse/pattern.h"

namespace meshik::sparse {

// Column j of C = P A P^T holds its rows i >= j, in no particular order. `source[p]` is the
// index into CscMatrix::values of the entry stored at position p, so that the values of a
// matrix with the same pattern are gathered without permuting again.
struct PermutedLower {
  Pattern pattern;
  std::vector<int> source;  // nnz(C) indices into CscMatrix::values
};

// a: n by n, lower triangle read; inverse_perm: n entries, inverse_perm[original] = new index.
PermutedLower permute_lower(const CscMatrix& a, const std::vector<int>& inverse_perm);

}  // namespace meshik::sparse
