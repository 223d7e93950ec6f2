// Triangular solves with the supernodal factor, many right-hand sides at once.
#pragma once

#include <vector>

#include "sparse/symbolic.h"

namespace meshik::sparse {

// x: n by nrhs row-major, in the factor's (permuted) order. Overwrites x with L^{-1} x.
void forward_solve(const SymbolicFactor& f, const std::vector<double>& values, double* x, int nrhs);

// x: n by nrhs row-major, in the factor's order. Overwrites x with L^{-T} x.
void backward_solve(const SymbolicFactor& f, const std::vector<double>& values, double* x, int nrhs);

}  // namespace meshik::sparse
