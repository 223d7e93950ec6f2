// Small dense kernels of the supernodal factorization, on column-major blocks.
#pragma once

namespace meshik::sparse {

// panel: rows by cols column-major (leading dimension rows), rows >= cols, holding the lower
// part of a symmetric cols by cols block on top of the rows below it. Overwrites it with the
// Cholesky factor L11 of the top block and L21 = A21 L11^{-T} below.
// Returns -1 on success, or the first column whose pivot is not positive (panel then partly
// overwritten). team: threads for a large panel (1: serial); the values are the same bits for any.
int factor_panel(double* panel, int rows, int cols, int team = 1);

// l21: m by k column-major with leading dimension ld. Writes u = -L21 L21^T, m by m, as its
// packed lower triangle (column q holds rows q..m-1, columns one after another). team: threads
// for a large product (1: serial); the values are the same bits for any.
void negative_lower_product(const double* l21, int ld, int m, int k, double* u, int team = 1);

// Offset of column q in the packed lower triangle of an m by m matrix.
inline long packed_column_offset(int m, int q) { return static_cast<long>(q) * (2L * m - q + 1) / 2; }

}  // namespace meshik::sparse
