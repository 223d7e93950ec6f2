// SparseCholesky: ties the analysis, the numeric factorization and the solves together.
#include "meshik/sparse_cholesky.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "sparse/analysis.h"
#include "sparse/input_check.h"
#include "sparse/numeric.h"
#include "sparse/simd.h"
#include "sparse/subtree_schedule.h"
#include "sparse/triangular_solve.h"
#include "thread_count.h"

namespace meshik {

using namespace sparse;

namespace {

// An analysed pattern (values empty; kept to check that factorize() gets the same one), its
// analysis and the subtrees of the factorization and the backward solve, shared by every
// SparseCholesky analysed like the one that made it.
struct AnalyzedPattern {
  CscMatrix pattern;
  Analysis analysis;
  SubtreeSchedule schedule;
};

}  // namespace

struct SparseCholesky::Impl {
  std::shared_ptr<const AnalyzedPattern> pattern;
  FactorValues factor;
  bool factorized = false;

  // Starts over with an analysed pattern (no factorization yet).
  void reset(std::shared_ptr<const AnalyzedPattern> analyzed) {
    pattern = std::move(analyzed);
    factor = FactorValues();
    factorized = false;
  }
  // The analysis (an empty one before analyze()).
  const Analysis& analysis() const {
    static const Analysis kNone;
    return pattern ? pattern->analysis : kNone;
  }
};

namespace {

// Throws unless a factorization is available (factorized) and (stride, columns) suit the
// in-order solves.
void check_in_order_arguments(bool factorized, int stride, int columns) {
  if (!factorized) throw std::logic_error("SparseCholesky: solve without a successful factorize()");
  if (stride % kLanes != 0 || columns < 0 || columns > stride)
    throw std::invalid_argument("SparseCholesky: in-order solve with stride " + std::to_string(stride) +
                                " and columns " + std::to_string(columns) +
                                " (need stride = padded_width(m) and 0 <= columns <= stride)");
}

}  // namespace

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const CscMatrix& a) {
  check_lower_input(a);
  auto analyzed = std::make_shared<AnalyzedPattern>();
  analyzed->analysis = analyze_pattern(a);
  // Balanced for the cores (at least 2, also when analysed inside a parallel region).
  analyzed->schedule = subtree_schedule(analyzed->analysis.symbolic, std::max(2, thread_count(0)));
  analyzed->pattern.rows = a.rows;
  analyzed->pattern.cols = a.cols;
  analyzed->pattern.col_start = a.col_start;
  analyzed->pattern.row_index = a.row_index;
  impl_->reset(std::move(analyzed));
}

void SparseCholesky::share_analysis(const SparseCholesky& other) {
  if (!other.impl_->pattern) throw std::logic_error("SparseCholesky::share_analysis: the other has no analysis");
  impl_->reset(other.impl_->pattern);
}

void SparseCholesky::factorize(const CscMatrix& a, int threads) {
  Impl& s = *impl_;
  if (!s.pattern) throw std::logic_error("SparseCholesky::factorize: no analyze() or share_analysis() first");
  if (a.rows != a.cols || a.col_start != s.pattern->pattern.col_start || a.row_index != s.pattern->pattern.row_index)
    throw std::invalid_argument(
        "SparseCholesky::factorize: the matrix pattern differs from the one given to analyze()");
  factorize_values(a.values, threads);
}

void SparseCholesky::factorize_values(const std::vector<double>& values, int threads) {
  Impl& s = *impl_;
  if (!s.pattern) throw std::logic_error("SparseCholesky::factorize: no analyze() or share_analysis() first");
  if (values.size() != s.pattern->pattern.row_index.size())
    throw std::invalid_argument("SparseCholesky::factorize: values has " + std::to_string(values.size()) +
                                " entries, expected " + std::to_string(s.pattern->pattern.row_index.size()));
  s.factorized = false;
  factorize_numeric(s.analysis(), values, s.factor, &s.pattern->schedule, thread_count(threads));
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
  if (nrhs == 0) return;
  const int n = size();
  const std::vector<int>& perm = s.analysis().perm;
  const size_t width = static_cast<size_t>(nrhs);
  // Permuted copy of b with rows padded to whole vectors, starting on a cache line (rows of
  // 16 doubles then span two lines, not three: measured 12% faster). Reused per thread: a
  // fresh buffer would cost page faults on every solve.
  const int stride = round_up_to_lanes(nrhs);
  constexpr size_t kLineDoubles = 64 / sizeof(double);
  thread_local std::vector<double> buffer;
  buffer.resize(static_cast<size_t>(n) * stride + kLineDoubles);
  const size_t misalignment = reinterpret_cast<uintptr_t>(buffer.data()) / sizeof(double) % kLineDoubles;
  double* x = buffer.data() + (kLineDoubles - misalignment) % kLineDoubles;
  for (int k = 0; k < n; ++k) {
    const double* from = b + perm[k] * width;
    double* to = x + static_cast<size_t>(k) * stride;
    for (int c = 0; c < nrhs; ++c) to[c] = from[c];
    for (int c = nrhs; c < stride; ++c) to[c] = 0.0;
  }
  forward_solve(s.analysis(), s.factor, x, stride, stride);
  backward_solve(s.analysis(), s.factor, x, stride, stride);
  for (int k = 0; k < n; ++k) {
    const double* from = x + static_cast<size_t>(k) * stride;
    double* to = b + perm[k] * width;
    for (int c = 0; c < nrhs; ++c) to[c] = from[c];
  }
}

const std::vector<int>& SparseCholesky::permutation() const { return impl_->analysis().perm; }

int SparseCholesky::padded_width(int nrhs) { return round_up_to_lanes(nrhs); }

void SparseCholesky::forward_solve_in_order(double* x, int stride, int columns, int threads) const {
  check_in_order_arguments(impl_->factorized, stride, columns);
  forward_solve(impl_->analysis(), impl_->factor, x, stride, columns, thread_count(threads),
                &impl_->pattern->schedule);
}

void SparseCholesky::backward_solve_in_order(double* x, int stride, int columns, int threads) const {
  check_in_order_arguments(impl_->factorized, stride, columns);
  backward_solve(impl_->analysis(), impl_->factor, x, stride, columns, thread_count(threads),
                 &impl_->pattern->schedule);
}

void SparseCholesky::backward_solve_rows_in_order(double* x, int stride, int columns,
                                                  const std::vector<int>& rows, int threads) const {
  check_in_order_arguments(impl_->factorized, stride, columns);
  for (int r : rows)
    if (r < 0 || r >= size())
      throw std::invalid_argument("SparseCholesky: backward solve row " + std::to_string(r) + " out of range [0, " +
                                  std::to_string(size()) + ")");
  backward_solve(impl_->analysis(), impl_->factor, reach_to_roots(impl_->analysis(), rows), x, stride, columns,
                 thread_count(threads), &impl_->pattern->schedule);
}

int SparseCholesky::size() const { return static_cast<int>(impl_->analysis().perm.size()); }

long long SparseCholesky::factor_nonzeros() const { return impl_->analysis().factor_nonzeros; }

namespace {

template <typename T>
size_t bytes_of(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

size_t SparseCholesky::analysis_bytes() const {
  if (!impl_->pattern) return 0;
  const AnalyzedPattern& p = *impl_->pattern;
  const Analysis& a = p.analysis;
  const SimplicialPrefix& prefix = a.prefix;
  const SymbolicFactor& f = a.symbolic;
  const SubtreeSchedule& t = p.schedule;
  return bytes_of(p.pattern.col_start) + bytes_of(p.pattern.row_index) + bytes_of(a.perm) +
         bytes_of(a.lower.pattern.col_start) + bytes_of(a.lower.pattern.row_index) + bytes_of(a.lower.source) +
         bytes_of(prefix.diagonal) + bytes_of(prefix.row_start) + bytes_of(prefix.rows) + bytes_of(prefix.below) +
         bytes_of(prefix.update_start) + bytes_of(prefix.update) + bytes_of(f.first_column) + bytes_of(f.row_start) +
         bytes_of(f.rows) + bytes_of(f.value_start) + bytes_of(f.parent) + bytes_of(f.child_start) +
         bytes_of(f.children) + bytes_of(t.top) + bytes_of(t.first) + bytes_of(t.root) + bytes_of(t.stack) +
         bytes_of(t.top_row) + bytes_of(t.top_pass);
}

const CscMatrix& SparseCholesky::analyzed_pattern() const {
  static const CscMatrix kNone;
  return impl_->pattern ? impl_->pattern->pattern : kNone;
}

}  // namespace meshik
