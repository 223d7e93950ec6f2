// Triangular solves with the factor (simplicial prefix, then supernodes), many right-hand
// sides at once.
#pragma once

#include "sparse/analysis.h"
#include "sparse/numeric.h"

namespace meshik::sparse {

// x: n rows of `stride` doubles (stride a multiple of kLanes, see simd.h), in the factor's
// (permuted) order; every column of x is a right-hand side. Overwrites the first `columns`
// (<= stride) columns of x, rounded up to whole vectors, with L^{-1} x; the others are untouched.
void forward_solve(const Analysis& analysis, const FactorValues& factor, double* x, int stride,
                   int columns);

// As forward_solve, with L^{-T} x.
void backward_solve(const Analysis& analysis, const FactorValues& factor, double* x, int stride,
                    int columns);

}  // namespace meshik::sparse
