// Proper polar decompositions and rotation logs of a batch of triangles' deformation gradients, in
// closed form.
//
// A triangle's deformation gradient T = V~ V^{-1} (triangle_frames.h) takes the rest frame
// [u1 u2 n] (U = [u1 u2]: the rest plane basis, n: the unit normal) to the deformed triangle's own
// frame [v1 v2 m] (v1 along its first edge, m its unit normal, v2 = m x v1):
//   T = [v1 v2 m] diag(A, sigma) [u1 u2 n]^T,
// with A = E~ E^{-1} (2 by 2: the deformed edges in their plane coordinates times the rest ones'
// inverse; upper triangular with a positive diagonal) and sigma = sqrt(deformed area / rest area).
// So T's proper polar factors are those of A (a 2D rotation R2 by atan2(-A12, A11 + A22)) with the
// identity on the normals: R = [v1 v2] R2 U^T + m n^T, and (S - I) U = U (R2^T A - I). No
// iteration. Lanes whose T is (near) singular (a collapsed deformed triangle) are handed to
// polar_decomposition (so3.h), the SVD. Logs near a half turn (angle >= 2 pi / 3) come from
// so3_log, the others from the lanes' own atan2.
#pragma once

#include "triangle_frames.h"

namespace meshik {

// Triangles a batch holds (one AVX-512 register of doubles per entry).
constexpr int kPolarLanes = kGradientLanes;

// frames: the rest triangles' (their gradient read; their plane bases, which the features take
// over, are plane_basis: TriangleFrames::plane_basis's layout, all triangles); triangles
// (#F by 3) and vertices (#V by 3): the deformed mesh; count (1 <= count <= kPolarLanes) triangles
// from first (a multiple of kPolarLanes). Writes for each, in lanes alike, the rotation R of its
// deformation gradient's proper polar decomposition T = R S (9 rows, R row-major, det +1),
// (S - I) U (6 rows, 3 by 2 row-major) and so3_log(R) (3 rows); lanes past count hold no result.
// Each result depends only on its triangle (no thread or call order enters).
void triangle_polar_and_log_batch(const TriangleFrames& frames, const double* plane_basis, const int* triangles,
                                  const double* vertices, int first, int count, double (&rotation)[9][kPolarLanes],
                                  double (&plane_stretch)[6][kPolarLanes], double (&log)[3][kPolarLanes]);

}  // namespace meshik
