// The symmetric permutation P A P^T of a matrix given by its lower triangle.
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"
#include "sparse/pattern.h"

namespace meshik::sparse {

// The lower triangle of `a` (entries above the diagonal dropped), pattern only.
Pattern lower_pattern(const CscMatrix& a);

// Which triangle of a symmetric matrix is stored.
enum class Triangle { kLower, kUpper };

// One triangle of C = P A P^T: column j of C holds its rows i >= j (kLower) or i <= j (kUpper),
// in no particular order. `source[p]` is the index into CscMatrix::values of the entry stored at
// position p, so that the values of a matrix with the same pattern are gathered without
// permuting again.
struct PermutedMatrix {
  Pattern pattern;
  std::vector<int> source;  // nnz(C) indices into CscMatrix::values
};

// a: n by n, lower triangle read; inverse_perm: n entries, inverse_perm[original] = new index.
PermutedMatrix permute_symmetric(const CscMatrix& a, const std::vector<int>& inverse_perm,
                                 Triangle triangle);

// Returns the transpose of an n by n pattern, rows sorted in every column.
Pattern transpose(const Pattern& p);

}  // namespace meshik::sparse
