// MeshIK's own sparse Cholesky factorization P A P^T = L L^T of a symmetric positive definite
// matrix: fill-reducing ordering, elimination tree, symbolic analysis (reusable while only the
// values change), numeric factorization and multi-right-hand-side solves.
//
// How (cpp_core/src/sparse/, one step per file):
//   analysis.cpp        nodes whose neighbours form a clique first (no fill: MeshIK's 4th-vertex
//                       unknowns), then SuiteSparse AMD on the rest, postordered by its
//                       elimination tree (elimination_tree.cpp, column_counts.cpp);
//                       supernodes with relaxed amalgamation (supernodes.cpp) and their row
//                       structures (symbolic.cpp).
//   numeric.cpp         the clique nodes eliminated directly on the values (simplicial_prefix.cpp),
//                       then a multifrontal supernodal factorization with register-tiled dense
//                       kernels (dense_kernels.cpp, vectorized with simd.h), independent subtrees
//                       of the elimination tree on several threads (subtree_schedule.cpp).
//   triangular_solve.cpp  forward and back substitution over the supernodes, all right-hand
//                       sides of a pass together (16 per chunk), the factor read once per chunk.
// factorize() and the in-order solves take a thread count (serial inside an OpenMP parallel
// region, so callers on several threads never oversubscribe the cores); one object is not safe for
// concurrent analyze/factorize, but concurrent solve() calls on a factored object are (each thread
// has its own work buffer).
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

namespace meshik {

// Compressed sparse column matrix. For SparseCholesky only the lower triangle (row >= col) is
// read; entries above the diagonal are ignored. Row indices within a column are sorted and
// unique, and every column stores its diagonal entry.
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
  // the n x n lower triangle `a`. Values are not read (`a` may have none). Throws
  // std::invalid_argument naming the column or entry when `a` is malformed (not square, indices
  // unsorted / repeated / out of range, a diagonal entry missing, sizes inconsistent).
  void analyze(const CscMatrix& a);
  // Takes `other`'s analysis (shared, not copied; other must have one, else std::logic_error)
  // for matrices of its pattern: many factorizations of one pattern (a mesh's system for
  // several handle sets) analyse it once. Drops any factorization this one held.
  void share_analysis(const SparseCholesky& other);
  // Numeric factorization of `a`, which must have the pattern given to analyze() (else
  // std::invalid_argument). Throws NotPositiveDefinite naming the (original) column whose pivot
  // is not positive; solve() is then unavailable until a factorization succeeds.
  // threads: 1 = serial, 0 = all cores, n = up to n threads, over independent subtrees of the
  // elimination tree; the factor (and any error) is the same bits for any count.
  void factorize(const CscMatrix& a, int threads = 1);
  // factorize() for the matrix of the analysed pattern with these values (one per entry of
  // analyzed_pattern(), in its order): the pattern is neither given again nor compared, so a
  // caller that keeps only the values stores the pattern once. Throws std::invalid_argument for
  // a wrong count, else as factorize().
  void factorize_values(const std::vector<double>& values, int threads = 1);
  // analyze() then factorize().
  void compute(const CscMatrix& a);

  // Solves A X = B in place. b: n by nrhs row-major (row i holds the nrhs values of unknown i),
  // so every right-hand side is carried through one pass over the factor. Throws
  // std::logic_error without a successful factorize().
  void solve(double* b, int nrhs) const;

  // The factor's row order: its row k is unknown permutation()[k] (n entries).
  const std::vector<int>& permutation() const;
  // The row width the in-order solves need for nrhs right-hand sides (nrhs rounded up to whole
  // SIMD vectors).
  static int padded_width(int nrhs);
  // The two halves of solve() for callers that keep their right-hand sides in the factor's row
  // order, so no permuted copy is made: x is n rows of `stride` doubles (stride = padded_width(m)
  // for some m; rows starting on 64-byte boundaries are fastest), row k holding unknown
  // permutation()[k]. Columns [0, columns) (columns <= stride) are overwritten with L^{-1} x
  // (forward) or L^{-T} x (backward), where A = P^T L L^T P; those from padded_width(columns) on
  // are untouched, and the padding columns between are either solved too or untouched. Since
  // B^T A^{-1} C = (L^{-1} P B)^T (L^{-1} P C), products with A^{-1} need only the forward half.
  // threads: 1 = serial, 0 = all cores, n = up to n threads over independent subtrees of the
  // elimination tree (the forward half then shares the top of the tree's rows by groups of whole
  // SIMD vectors of columns). The result is the same bits for any count, and serial when called
  // inside an OpenMP parallel region.
  // Throw std::logic_error without a successful factorize(), std::invalid_argument for a bad
  // stride or column count.
  void forward_solve_in_order(double* x, int stride, int columns, int threads = 1) const;
  void backward_solve_in_order(double* x, int stride, int columns, int threads = 1) const;
  // backward_solve_in_order where only the rows `rows` (factor order, each in [0, n)) of the
  // result are wanted: runs the pass over their elimination-tree paths to the roots only, which
  // overwrites those rows exactly, and the paths' other rows too; x's rows off the paths are left
  // as they were. Throws as backward_solve_in_order, and std::invalid_argument for a row out of
  // range.
  void backward_solve_rows_in_order(double* x, int stride, int columns, const std::vector<int>& rows,
                                    int threads = 1) const;

  int size() const;
  long long factor_nonzeros() const;  // nnz(L), diagonal included
  // The pattern given to analyze() (rows, cols, col_start, row_index; values empty), shared by
  // every SparseCholesky analysed like this one; an empty matrix before analyze().
  const CscMatrix& analyzed_pattern() const;
  // Bytes held by the analysis (the pattern, ordering, symbolic factor and schedules; shared by
  // every SparseCholesky sharing it), 0 before analyze().
  size_t analysis_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshik
