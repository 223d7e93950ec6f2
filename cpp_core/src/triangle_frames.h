// Per-triangle rest geometry: an orthonormal basis of the triangle's plane and the in-plane
// gradient coefficients of its corners, from which the inverse rest frame follows.
//
// Notation (DESIGN.md section 2): for corners v1, v2, v3 the fourth vertex is
//   v4 = v1 + (v2 - v1) x (v3 - v1) / sqrt(|(v2 - v1) x (v3 - v1)|),
// the frame is V = [v2 - v1, v3 - v1, v4 - v1] and a deformed copy's gradient is T = V~ V^{-1}.
// In the plane basis U = [u1 u2] and the unit normal n = u1 x u2, V = [U n] diag(E, sqrt(p s)) with
// E = U^T [v2 - v1, v3 - v1] = [p q; 0 s] (p, s > 0, p s twice the area), so
// V^{-1} = diag(E^{-1}, 1 / sqrt(p s)) [U n]^T: nothing beyond U and E^{-1} needs storing.
//
// Eliminating the fourth vertex: T's component along the rest normal is matched exactly by the
// deformed fourth vertex, so only T U matters, with U (3 by 2) an orthonormal basis of the rest
// plane. T U equals the in-plane gradient Q(X) = sum_q X[corner q] g_q^T of the corner positions
// alone (g_q: 2-vectors, g_1 = -(g_2 + g_3)).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "page_arrays.h"
#include "simd_clones.h"

namespace meshik {

// Entries stored per triangle for its in-plane gradient coefficients: g_2 (2) and g_3's second
// entry; g_3's first is 0 (E^{-1} is upper triangular) and g_1 = -(g_2 + g_3).
constexpr int kGradientEntries = 3;

// stored: a triangle's kGradientEntries gradient entries. Fills g (3 corners by 2: g_1, g_2, g_3)
// with the values compute_triangle_frames derives them as, bit for bit.
inline void corner_gradients(const double* stored, double* g) {
  g[2] = stored[0];
  g[3] = stored[1];
  g[4] = 0.0;
  g[5] = stored[2];
  g[0] = -(g[2] + g[4]);
  g[1] = -(g[3] + g[5]);
}

struct TriangleFrames {
  int num_triangles = 0;
  // #F by kGradientEntries: the in-plane gradient coefficients, g_q of each corner read with
  // corner_gradients (half the memory of all six: 26 MB at 1.08M triangles).
  PageArray<double> gradient;
  // U (3 by 2 row-major), whose columns are an orthonormal basis of the rest plane, in batches of
  // kGradientLanes triangles: batch b holds 6 rows of kGradientLanes, entry (b 6 + row)
  // kGradientLanes + lane for triangle j = b kGradientLanes + lane, zero in the last batch's
  // padding lanes (ExampleFeatures::plane_basis's layout: the features take it over).
  PageArray<double> plane_basis;
};

// rest: #V by 3 positions; triangles: #F by 3 indices of non-degenerate triangles. team: threads
// (1: serial), over batches of triangles; each triangle's frame is the same bits for any team.
TriangleFrames compute_triangle_frames(const double* rest, const int* triangles, int num_triangles, int team = 1);

// (e1 x e2) / sqrt(|e1 x e2|): the fourth vertex minus the first; zero for a degenerate triangle.
Eigen::Vector3d fourth_vertex_offset(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2);

// gradient: #F by kGradientEntries (TriangleFrames::gradient's values); plane_basis:
// TriangleFrames::plane_basis's layout. Writes triangle j's inverse rest frame V^{-1} (fourth vertex
// included) as 9 row-major entries: the two rows of E^{-1} U^T, then n^T / sqrt(p s).
void rest_frame_inverse(const double* gradient, const double* plane_basis, int j, double (&inverse)[9]);

// The deformation gradient T = V~ V^{-1} (3 by 3) of triangle j of frames, deformed to corner
// positions taken from vertices (#V by 3) through triangles (#F by 3).
Eigen::Matrix3d deformation_gradient(const TriangleFrames& frames, const int* triangles,
                                     const double* vertices, int j);

// Triangles a deformation_gradients call takes at once (their arithmetic is SIMD).
constexpr int kGradientLanes = 8;

// The edges e1 = v2 - v1 and e2 = v3 - v1 of the count (1 <= count <= kGradientLanes) triangles
// first, first + 1, ... of the mesh with positions `vertices` (#V by 3), one lane each (lanes
// past count repeat the last triangle).
MESHIK_LANE_INLINE void edge_lanes(const double* vertices, const int* triangles, int first, int count,
                                   double (&e1)[3][kGradientLanes], double (&e2)[3][kGradientLanes]) {
  for (int l = 0; l < kGradientLanes; ++l) {
    const int j = first + (l < count ? l : count - 1);
    const double* a = vertices + 3 * static_cast<size_t>(triangles[3 * j]);
    const double* b = vertices + 3 * static_cast<size_t>(triangles[3 * j + 1]);
    const double* c = vertices + 3 * static_cast<size_t>(triangles[3 * j + 2]);
    for (int r = 0; r < 3; ++r) {
      e1[r][l] = b[r] - a[r];
      e2[r][l] = c[r] - a[r];
    }
  }
}

// deformation_gradient for the count (1 <= count <= kGradientLanes) triangles first, first + 1,
// ..., their rest frames given as to rest_frame_inverse: writes entry (r, c) of lane l's gradient
// to t[3 r + c][l] (lanes past count repeat the last triangle's).
void deformation_gradients(const double* gradient, const double* plane_basis, const int* triangles,
                           const double* vertices, int first, int count, double (&t)[9][kGradientLanes]);

// An Eigen view of triangle j's plane basis U (3 by 2) in frames.
inline Eigen::Map<const Eigen::Matrix<double, 3, 2, Eigen::RowMajor>, Eigen::Unaligned,
                  Eigen::InnerStride<kGradientLanes>>
plane_basis_of(const TriangleFrames& frames, int j) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 2, Eigen::RowMajor>, Eigen::Unaligned,
                    Eigen::InnerStride<kGradientLanes>>(
      frames.plane_basis.data() + 6 * kGradientLanes * static_cast<size_t>(j / kGradientLanes) + j % kGradientLanes);
}

}  // namespace meshik
