// Simplicial (column by column) Cholesky factor L with A = L L^T, computed row by row
// ("up-looking"), and its multi-right-hand-side triangular solves.
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// L in compressed columns; the diagonal is the first entry of every column.
struct SimplicialFactor {
  int n = 0;
  std::vector<int> col_start;  // n + 1 offsets, from the column counts
  std::vector<int> row_index;  // nnz(L)
  std::vector<double> values;  // nnz(L)
};

// Allocates L for the column counts (n entries, diagonal included).
SimplicialFactor allocate_simplicial(const std::vector<int>& counts);

// upper: the upper triangle of P A P^T (column k: rows i <= k); values[p] is the value of
// entry p of `upper`; parent: its elimination tree; original_column[k] names pivot k in errors.
// Fills `l`. Throws NotPositiveDefinite naming original_column[k] for the failing pivot k.
void factorize_up_looking(const Pattern& upper, const double* values,
                          const std::vector<int>& parent,
                          const std::vector<int>& original_column, SimplicialFactor& l);

// Solves L Y = X then L^T Z = Y in place. x: n by nrhs row-major.
void solve_simplicial(const SimplicialFactor& l, double* x, int nrhs);

}  // namespace meshik::sparse
