// Triangular solves with the factor (simplicial prefix, then supernodes), many right-hand
// sides at once.
#pragma once

#include <vector>

#include "sparse/analysis.h"
#include "sparse/numeric.h"
#include "sparse/subtree_schedule.h"

namespace meshik::sparse {

// x: n rows of `stride` doubles (stride a multiple of kLanes, see simd.h), in the factor's
// (permuted) order; every column of x is a right-hand side. Overwrites the first `columns`
// (<= stride) columns of x, rounded up to whole vectors (to half a vector when they fit in one),
// with L^{-1} x; the others are untouched.
// team: threads (a thread_count). Without a schedule each solves a group of whole vectors of
// columns; with one (subtree_schedule of analysis.symbolic), each a subtree at a time on all
// columns, then the top's rows by groups of columns. The result is the same bits for any team.
void forward_solve(const Analysis& analysis, const FactorValues& factor, double* x, int stride,
                   int columns, int team = 1, const SubtreeSchedule* schedule = nullptr);

// As forward_solve, with L^{-T} x; with team > 1 and a schedule (subtree_schedule of
// analysis.symbolic), the schedule's subtrees run on the team's threads instead of the groups of
// columns (the same bits either way).
void backward_solve(const Analysis& analysis, const FactorValues& factor, double* x, int stride,
                    int columns, int team = 1, const SubtreeSchedule* schedule = nullptr);

// The rows (factor order) and supernodes on the elimination-tree paths from `rows` to the roots:
// row i of L^{-T} x depends only on x's rows on i's path, so the backward pass over this part
// alone gives those rows exactly.
struct Reach {
  std::vector<char> row;        // n: on a path
  std::vector<char> supernode;  // #supernodes: holds a column on a path
};
Reach reach_to_roots(const Analysis& analysis, const std::vector<int>& rows);

// backward_solve over the part of the factor in `reach` only: overwrites the reached rows of x
// with those of L^{-T} x and leaves the others as they were.
void backward_solve(const Analysis& analysis, const FactorValues& factor, const Reach& reach, double* x,
                    int stride, int columns, int team = 1, const SubtreeSchedule* schedule = nullptr);

}  // namespace meshik::sparse
