// MeshIK's own sparse Cholesky factorization A = L L^T (or L D L^T) of a symmetric positive
// definite matrix: fill-reducing ordering, elimination tree, symbolic analysis (reusable while
// only the values change), numeric factorization and multi-right-hand-side solves.
#pragma once

#include <memory>
#include <stdexcept>
#include <vector>

namespace meshik {

// Compressed sparse column matrix. For SparseCholesky only the lower triangle (row >= col) is
// read; entries above the diagonal are ignored. Row indices within a column are sorted and unique.
struct CscMatrix {
  int rows = 0;
  int cols = 0;
  std::vector<int> col_start;  // cols + 1 offsets into row_index / values
  std::vector<int> row_index;  // nnz row indices
  std::vector<double> values;  // nnz values
};

// The matrix is not (numerically) positive definite; names the pivot column.
class NotPositiveDefinite : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // Ordering, elimination tree, column counts and the factor's structure for the pattern of
  // the n x n lower triangle `a`. Values are not read.
  void analyze(const CscMatrix& a);
  // Numeric factorization of `a`, which must have the pattern given to analyze().
  // Throws NotPositiveDefinite.
  void factorize(const CscMatrix& a);
  // analyze() then factorize().
  void compute(const CscMatrix& a);

  // Solves A X = B in place. b: n by nrhs row-major (row i holds the nrhs values of unknown i),
  // so every right-hand side is carried through one pass over the factor.
  void solve(double* b, int nrhs) const;

  int size() const;
  long long factor_nonzeros() const;  // nnz(L), diagonal included

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshik
