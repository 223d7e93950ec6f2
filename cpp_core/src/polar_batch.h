// Proper polar decompositions and rotation logs of a batch of 3x3 matrices at once.
//
// The batch runs Newton's iteration for the orthogonal polar factor, X <- (g X + X^{-T} / g) / 2
// (Higham; g: Frobenius-norm scaling while far from converged), on all lanes together, which the
// compiler turns into SIMD instructions: about 10x faster than a Jacobi SVD per matrix. Lanes it
// cannot serve exactly as polar_decomposition (so3.h) would are done by that one: a determinant
// that is not clearly positive (a reflection or a degenerate matrix, whose proper factor differs
// from the orthogonal one), or no convergence. Logs near a half turn (angle >= 2 pi / 3) come
// from so3_log, the others from the lanes' own atan2.
#pragma once

namespace meshik {

// Matrices a batch holds (one AVX-512 register of doubles per entry).
constexpr int kPolarLanes = 8;

// t: count (<= kPolarLanes) matrices in lanes, entry (r, c) of lane l at t[3 r + c][l]. Writes
// for each, in lanes alike, its proper polar decomposition t = rotation stretch (rotation:
// det +1; stretch: symmetric; 9 rows each) and log (so3_log(rotation), 3 rows); lanes past
// count hold no result. Each result depends only on the batch's matrices (no thread or call
// order enters).
void polar_and_log_batch(const double (&t)[9][kPolarLanes], int count, double (&rotation)[9][kPolarLanes],
                         double (&stretch)[9][kPolarLanes], double (&log)[3][kPolarLanes]);

}  // namespace meshik
