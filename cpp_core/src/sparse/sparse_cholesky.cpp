// SparseCholesky: ties the ordering, the symbolic analysis, the numeric factorization and the
// solves together.
#include "meshik/sparse_cholesky.h"

#include <algorithm>
#include <string>

#include "sparse/column_counts.h"
#include "sparse/elimination_tree.h"
#include "sparse/input_check.h"
#include "sparse/numeric.h"
#include "sparse/ordering.h"
#include "sparse/permuted_matrix.h"
#include "sparse/supernodes.h"
#include "sparse/symbolic.h"
#include "sparse/triangular_solve.h"

namespace meshik {

using namespace sparse;

struct SparseCholesky::Impl {
  // The analysed pattern, to check that factorize() gets the same one.
  std::vector<int> input_col_start, input_row_index;
  std::vector<int> perm;   // perm[k]: original index of pivot k (fill-reducing, then postordered)
  PermutedMatrix lower;    // lower triangle of P A P^T, with sources into A's values
  SymbolicFactor symbolic;
  std::vector<double> values;  // the supernodes' dense blocks
  bool factorized = false;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const CscMatrix& a) {
  check_lower_input(a);
  Impl fresh;
  fresh.input_col_start = a.col_start;
  fresh.input_row_index = a.row_index;
  // Minimum degree, then a postorder of its elimination tree so that supernodes are runs of
  // consecutive columns.
  const std::vector<int> amd = minimum_degree_ordering(lower_pattern(a));
  const Pattern upper = permute_symmetric(a, invert_permutation(amd), Triangle::kUpper).pattern;
  const std::vector<int> amd_parent = elimination_tree(upper);
  const std::vector<int> post = tree_postorder(amd_parent);
  const std::vector<int> amd_counts = column_counts(transpose(upper), amd_parent, post);
  const int n = a.cols;
  fresh.perm.resize(n);
  std::vector<int> counts(n);
  for (int k = 0; k < n; ++k) {
    fresh.perm[k] = amd[post[k]];
    counts[k] = amd_counts[post[k]];
  }
  const std::vector<int> parent = relabel_tree(amd_parent, post);
  fresh.lower = permute_symmetric(a, invert_permutation(fresh.perm), Triangle::kLower);
  fresh.symbolic = symbolic_factor(fresh.lower.pattern, find_supernodes(parent, counts), counts);
  *impl_ = std::move(fresh);
}

void SparseCholesky::factorize(const CscMatrix& a) {
  Impl& s = *impl_;
  if (a.rows != a.cols || a.col_start != s.input_col_start || a.row_index != s.input_row_index)
    throw std::invalid_argument(
        "SparseCholesky::factorize: the matrix pattern differs from the one given to analyze()");
  if (a.values.size() != a.row_index.size())
    throw std::invalid_argument("SparseCholesky::factorize: values has " +
                                std::to_string(a.values.size()) + " entries, expected " +
                                std::to_string(a.row_index.size()));
  s.factorized = false;
  const LowerValues values{&s.lower.pattern, s.lower.source.data(), a.values.data()};
  factorize_supernodal(s.symbolic, values, s.perm, s.values);
  s.factorized = true;
}

void SparseCholesky::compute(const CscMatrix& a) {
  analyze(a);
  factorize(a);
}

void SparseCholesky::solve(double* b, int nrhs) const {
  const Impl& s = *impl_;
  if (!s.factorized) throw std::logic_error("SparseCholesky::solve: no successful factorize()");
  if (nrhs < 0) throw std::invalid_argument("SparseCholesky::solve: nrhs must be >= 0");
  const int n = size();
  const size_t width = static_cast<size_t>(nrhs);
  // Reused per thread: a fresh buffer would cost page faults on every solve.
  thread_local std::vector<double> x;
  x.resize(static_cast<size_t>(n) * width);
  for (int k = 0; k < n; ++k) std::copy_n(b + s.perm[k] * width, width, x.data() + k * width);
  forward_solve(s.symbolic, s.values, x.data(), nrhs);
  backward_solve(s.symbolic, s.values, x.data(), nrhs);
  for (int k = 0; k < n; ++k) std::copy_n(x.data() + k * width, width, b + s.perm[k] * width);
}

int SparseCholesky::size() const { return static_cast<int>(impl_->perm.size()); }

long long SparseCholesky::factor_nonzeros() const { return impl_->symbolic.structural_nonzeros; }

}  // namespace meshik
