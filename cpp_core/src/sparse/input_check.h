// Validation of a CscMatrix handed to SparseCholesky.
#pragma once

#include "meshik/sparse_cholesky.h"

namespace meshik::sparse {

// Throws std::invalid_argument naming the offending column / entry when `a` is not a square
// compressed-column matrix with sorted, unique, in-range row indices, a diagonal entry in every
// column's lower part, and values.size() == row_index.size() (or no values: a pattern only).
void check_lower_input(const CscMatrix& a);

}  // namespace meshik::sparse
