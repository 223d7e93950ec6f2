// The examples' per-triangle features and their blend M(w) with its exact Jacobian dM/dw.
//
// Only T_j(w) U_j (3 by 2) enters the eliminated energy (triangle_frames.h), so the features are
// stored projected on the rest plane:
//   nonlinear: phi_ij = log R_ij (a consistent branch), D_ij = (S_ij - I) U_j
//              F_j(w) = exp(sum_i w_i phi_ij) (U_j + sum_i w_i D_ij)
//   linear:    L_ij = (T_ij - I) U_j,     F_j(w) = U_j + sum_i w_i L_ij
// with T_ij = R_ij S_ij the proper polar decomposition. w = 0 gives U_j (the rest pose) and
// w = e_i gives T_ij U_j (example i).
#pragma once

#include <vector>

#include "meshik/meshik.h"
#include "mesh_topology.h"
#include "so3.h"
#include "triangle_frames.h"

namespace meshik {

struct ExampleFeatures {
  int num_examples = 0;
  int num_triangles = 0;
  // #F by #E by 9: phi_ij (3), then D_ij (3 by 2 row-major).
  std::vector<double> nonlinear;
  // #F by #E by 6: L_ij (3 by 2 row-major).
  std::vector<double> linear;
  // #F by 6: U_j (3 by 2 row-major).
  std::vector<double> plane_basis;
};

// frames / adjacency / triangles (#F by 3): the rest mesh's; examples: #E pointers to #V by 3
// positions. consistent_branches = false keeps the principal rotation logs (for comparison only).
// progress(fraction) is called once per example.
ExampleFeatures compute_example_features(const TriangleFrames& frames,
                                         const TriangleAdjacency& adjacency, const int* triangles,
                                         const std::vector<const double*>& examples,
                                         const ProgressCallback& progress = {},
                                         bool consistent_branches = true);

// Number of doubles blend_triangle writes: the target and one derivative per example.
inline int blend_block_size(int num_examples) { return 6 * (num_examples + 1); }

// Blends triangle j's features with weights w (#E). Writes to out (blend_block_size doubles):
// F_j(w) (3 by 2 row-major), then dF_j/dw_i (3 by 2 row-major) for i = 0 .. #E-1.
inline void blend_triangle(const ExampleFeatures& features, FeatureSpace space, const double* w,
                           int j, double* out) {
  const int k = features.num_examples;
  const double* basis = features.plane_basis.data() + 6 * static_cast<size_t>(j);
  if (space == FeatureSpace::kLinear) {
    const double* l = features.linear.data() + 6 * static_cast<size_t>(j) * k;
    for (int e = 0; e < 6; ++e) out[e] = basis[e];
    for (int i = 0; i < k; ++i)
      for (int e = 0; e < 6; ++e) {
        out[e] += w[i] * l[6 * i + e];
        out[6 * (i + 1) + e] = l[6 * i + e];
      }
    return;
  }
  const double* f = features.nonlinear.data() + 9 * static_cast<size_t>(j) * k;
  double phi[3] = {0.0, 0.0, 0.0};
  double stretch[6];
  for (int e = 0; e < 6; ++e) stretch[e] = basis[e];
  for (int i = 0; i < k; ++i) {
    const double* fi = f + 9 * i;
    for (int e = 0; e < 3; ++e) phi[e] += w[i] * fi[e];
    for (int e = 0; e < 6; ++e) stretch[e] += w[i] * fi[3 + e];
  }
  const double x = phi[0], y = phi[1], z = phi[2];
  const RodriguesCoefficients r = rodrigues_coefficients(x * x + y * y + z * z);
  // R = I + a [phi]_x + b [phi]_x^2, row-major.
  const double rot[9] = {1.0 - r.b * (y * y + z * z), r.b * x * y - r.a * z, r.b * x * z + r.a * y,
                         r.b * x * y + r.a * z, 1.0 - r.b * (x * x + z * z), r.b * y * z - r.a * x,
                         r.b * x * z - r.a * y, r.b * y * z + r.a * x, 1.0 - r.b * (x * x + y * y)};
  // F = R (U + sum w_i D_i).
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 2; ++col)
      out[2 * row + col] = rot[3 * row] * stretch[col] + rot[3 * row + 1] * stretch[2 + col] +
                           rot[3 * row + 2] * stretch[4 + col];
  // dF/dw_i = psi_i x F (column by column) + R D_i with psi_i = J_l(phi) phi_i, because
  // d exp(phi)/dw_i = [J_l(phi) phi_i]_x exp(phi).
  for (int i = 0; i < k; ++i) {
    const double* fi = f + 9 * i;
    const double u0 = fi[0], u1 = fi[1], u2 = fi[2];
    const double c0 = y * u2 - z * u1, c1 = z * u0 - x * u2, c2 = x * u1 - y * u0;
    const double psi0 = u0 + r.b * c0 + r.c * (y * c2 - z * c1);
    const double psi1 = u1 + r.b * c1 + r.c * (z * c0 - x * c2);
    const double psi2 = u2 + r.b * c2 + r.c * (x * c1 - y * c0);
    const double* d = fi + 3;
    double* o = out + 6 * (i + 1);
    for (int col = 0; col < 2; ++col) {
      const double f0 = out[col], f1 = out[2 + col], f2 = out[4 + col];
      o[col] = psi1 * f2 - psi2 * f1 + rot[0] * d[col] + rot[1] * d[2 + col] + rot[2] * d[4 + col];
      o[2 + col] =
          psi2 * f0 - psi0 * f2 + rot[3] * d[col] + rot[4] * d[2 + col] + rot[5] * d[4 + col];
      o[4 + col] =
          psi0 * f1 - psi1 * f0 + rot[6] * d[col] + rot[7] * d[2 + col] + rot[8] * d[4 + col];
    }
  }
}

}  // namespace meshik
