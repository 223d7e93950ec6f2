// SparseCholesky: ties the ordering, the symbolic analysis, the numeric factorization and the
// solves together.
#include "meshik/sparse_cholesky.h"

#include <algorithm>
#include <string>

#include "sparse/column_counts.h"
#include "sparse/elimination_tree.h"
#include "sparse/input_check.h"
#include "sparse/ordering.h"
#include "sparse/permuted_matrix.h"
#include "sparse/simplicial_factor.h"

namespace meshik {

using namespace sparse;

struct SparseCholesky::Impl {
  // The analysed pattern, to check that factorize() gets the same one.
  std::vector<int> input_col_start, input_row_index;
  std::vector<int> perm;          // perm[k]: original index of pivot k
  PermutedMatrix upper;           // upper triangle of P A P^T, with sources into A's values
  std::vector<int> parent;        // elimination tree of P A P^T
  std::vector<int> counts;        // column counts of L
  SimplicialFactor factor;
  std::vector<double> permuted_values;  // values of `upper`, gathered per factorize()
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
  fresh.perm = minimum_degree_ordering(lower_pattern(a));
  fresh.upper = permute_symmetric(a, invert_permutation(fresh.perm), Triangle::kUpper);
  fresh.parent = elimination_tree(fresh.upper.pattern);
  const std::vector<int> post = tree_postorder(fresh.parent);
  fresh.counts = column_counts(transpose(fresh.upper.pattern), fresh.parent, post);
  fresh.factor = allocate_simplicial(fresh.counts);
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
  s.permuted_values.resize(s.upper.source.size());
  for (size_t p = 0; p < s.upper.source.size(); ++p)
    s.permuted_values[p] = a.values[s.upper.source[p]];
  factorize_up_looking(s.upper.pattern, s.permuted_values.data(), s.parent, s.perm, s.factor);
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
  std::vector<double> x(static_cast<size_t>(n) * width);
  for (int k = 0; k < n; ++k)
    std::copy_n(b + s.perm[k] * width, width, x.data() + k * width);
  solve_simplicial(s.factor, x.data(), nrhs);
  for (int k = 0; k < n; ++k)
    std::copy_n(x.data() + k * width, width, b + s.perm[k] * width);
}

int SparseCholesky::size() const { return static_cast<int>(impl_->perm.size()); }

long long SparseCholesky::factor_nonzeros() const {
  long long total = 0;
  for (int c : impl_->counts) total += c;
  return total;
}

}  // namespace meshik
