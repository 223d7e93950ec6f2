// Triangular solves with the supernodal factor, many right-hand sides at once.
#pragma once

#include <vector>

#include "sparse/symbolic.h"

namespace meshik::sparse {

// x: n rows of `stride` doubles (stride a multiple of kLanes, see simd.h), in the factor's
// (permuted) order; every column of x is a right-hand side. Overwrites x with L^{-1} x.
void forward_solve(const SymbolicFactor& f, const std::vector<double>& values, double* x, int stride);

// As forward_solve, overwrites x with L^{-T} x.
void backward_solve(const SymbolicFactor& f, const std::vector<double>& values, double* x, int stride);

}  // namespace meshik::sparse
