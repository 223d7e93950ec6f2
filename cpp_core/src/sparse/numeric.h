// Numeric factorization A = L L^T: the simplicial prefix, then the supernodal rest
// (multifrontal, on independent subtrees in parallel).
#pragma once

#include <vector>

#include "page_arrays.h"
#include "sparse/analysis.h"
#include "sparse/subtree_schedule.h"

namespace meshik::sparse {

// The factor's values.
struct FactorValues {
  std::vector<double> prefix_diagonal;  // prefix.size: L(u, u) of the simplicial prefix
  std::vector<double> prefix_below;     // prefix.rows.size(): its entries below the diagonal
  PageArray<double> supernodal;         // symbolic.value_start.back(): the supernodes' blocks
};

// a_values: the values of the matrix analysed by `analysis` (same pattern). Fills `factor`.
// schedule / team: see factorize_supernodal. Throws NotPositiveDefinite naming the original column
// of the first failing pivot.
void factorize_numeric(const Analysis& analysis, const std::vector<double>& a_values, FactorValues& factor,
                       const SubtreeSchedule* schedule = nullptr, int team = 1);

// Factorizes the supernodal columns into `values` (sized symbolic.value_start.back()),
// supernode by supernode in order: each supernode's block gathers its columns of the
// permuted lower triangle (`lower`, values `lower_values`, global numbering) and its
// children's update matrices, is factored densely, and leaves its own update matrix on a
// stack for its parent. With team > 1 threads (a thread_count) and a schedule
// (subtree_schedule of symbolic) of two or more subtrees, each subtree runs on one thread with
// its own stack, then the top supernode by supernode, the dense kernels of a large one split over
// the team in fixed pieces (a tree of fewer subtrees: every supernode so). Every supernode's
// arithmetic is the same, so the values are the same bits for any team, and so is the error (the
// first failing pivot in the serial order).
// original_column[k] names pivot k in the error. Throws NotPositiveDefinite.
void factorize_supernodal(const SymbolicFactor& symbolic, const Pattern& lower, const double* lower_values,
                          const std::vector<int>& original_column, PageArray<double>& values,
                          const SubtreeSchedule* schedule = nullptr, int team = 1);

// Throws NotPositiveDefinite naming the original column whose pivot is not positive.
[[noreturn]] void throw_not_positive_definite(int original_column);

}  // namespace meshik::sparse
