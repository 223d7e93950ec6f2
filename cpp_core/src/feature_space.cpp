// Precomputation of the examples' per-triangle features (polar decomposition, rotation logs with
// consistent branches, stretches projected on the rest planes) and their batched blend.
#include "feature_space.h"

#include <string>

#include "lane_math.h"
#include "rotation_branches.h"
#include "simd_clones.h"
#include "so3.h"

namespace meshik {

namespace {

// Writes the 3 by 2 row-major matrix m into rows [first_row, first_row + 6) of a lane-minor block.
void store_rows(const Eigen::Matrix<double, 3, 2>& m, double* block, int first_row, int lane) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 2; ++c) block[(first_row + 2 * r + c) * kLanes + lane] = m(r, c);
}

}  // namespace

ExampleFeatures compute_example_features(const TriangleFrames& frames,
                                         const TriangleAdjacency& adjacency, const int* triangles,
                                         const std::vector<const double*>& examples,
                                         const ProgressCallback& progress,
                                         bool consistent_branches) {
  const int m = frames.num_triangles;
  const int k = static_cast<int>(examples.size());
  ExampleFeatures features;
  features.num_examples = k;
  features.num_triangles = m;
  features.num_batches = (m + kLanes - 1) / kLanes;
  const size_t slots = static_cast<size_t>(features.num_batches) * kLanes;
  features.nonlinear.assign(9 * slots * k, 0.0);
  features.linear.assign(6 * slots * k, 0.0);
  features.plane_basis.assign(6 * slots, 0.0);
  for (int j = 0; j < m; ++j)
    store_rows(plane_basis_of(frames, j), features.plane_basis.data() + 6 * kLanes * (j / kLanes), 0,
               j % kLanes);

  std::vector<Eigen::Vector3d> logs(m);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < m; ++j) {
      const Eigen::Matrix3d t = deformation_gradient(frames, triangles, examples[i], j);
      const PolarDecomposition polar = polar_decomposition(t);
      logs[j] = so3_log(polar.rotation);
      const auto basis = plane_basis_of(frames, j);
      const size_t block = static_cast<size_t>(j / kLanes) * k + i;
      store_rows((polar.stretch - Eigen::Matrix3d::Identity()) * basis,
                 features.nonlinear.data() + 9 * kLanes * block, 3, j % kLanes);
      store_rows((t - Eigen::Matrix3d::Identity()) * basis, features.linear.data() + 6 * kLanes * block,
                 0, j % kLanes);
    }
    if (consistent_branches) choose_consistent_log_branches(adjacency, logs);
    for (int j = 0; j < m; ++j) {
      double* block = features.nonlinear.data() + 9 * kLanes * (static_cast<size_t>(j / kLanes) * k + i);
      for (int r = 0; r < 3; ++r) block[r * kLanes + j % kLanes] = logs[j](r);
    }
    if (progress && !progress(static_cast<double>(i + 1) / k, "example features"))
      throw Cancelled("cancelled while computing the features of example " + std::to_string(i));
  }
  return features;
}

MESHIK_SIMD_CLONES
void blend_batch(const ExampleFeatures& features, FeatureSpace space, const double* w, int batch,
                 double* out) {
  constexpr int L = kLanes;
  const int k = features.num_examples;
  const double* basis = features.plane_basis.data() + static_cast<size_t>(batch) * 6 * L;
  if (space == FeatureSpace::kLinear) {
    const double* lin = features.linear.data() + static_cast<size_t>(batch) * k * 6 * L;
    for (int e = 0; e < 6 * L; ++e) out[e] = basis[e];
    for (int i = 0; i < k; ++i)
      for (int e = 0; e < 6 * L; ++e) {
        out[e] += w[i] * lin[i * 6 * L + e];
        out[(i + 1) * 6 * L + e] = lin[i * 6 * L + e];
      }
    return;
  }
  const double* feature = features.nonlinear.data() + static_cast<size_t>(batch) * k * 9 * L;
  double phi[3][L] = {};
  double stretch[6][L];
  for (int e = 0; e < 6; ++e)
    for (int l = 0; l < L; ++l) stretch[e][l] = basis[e * L + l];
  for (int i = 0; i < k; ++i) {
    const double* f = feature + i * 9 * L;
    for (int r = 0; r < 3; ++r)
      for (int l = 0; l < L; ++l) phi[r][l] += w[i] * f[r * L + l];
    for (int e = 0; e < 6; ++e)
      for (int l = 0; l < L; ++l) stretch[e][l] += w[i] * f[(3 + e) * L + l];
  }
  double t2[L], a[L], b[L], c[L];
  for (int l = 0; l < L; ++l) t2[l] = phi[0][l] * phi[0][l] + phi[1][l] * phi[1][l] + phi[2][l] * phi[2][l];
  rodrigues_lanes<L>(t2, a, b, c);
  // R = I + a [phi]_x + b [phi]_x^2, row-major, per lane.
  double rot[9][L];
  for (int l = 0; l < L; ++l) {
    const double x = phi[0][l], y = phi[1][l], z = phi[2][l];
    rot[0][l] = 1.0 - b[l] * (y * y + z * z);
    rot[1][l] = b[l] * x * y - a[l] * z;
    rot[2][l] = b[l] * x * z + a[l] * y;
    rot[3][l] = b[l] * x * y + a[l] * z;
    rot[4][l] = 1.0 - b[l] * (x * x + z * z);
    rot[5][l] = b[l] * y * z - a[l] * x;
    rot[6][l] = b[l] * x * z - a[l] * y;
    rot[7][l] = b[l] * y * z + a[l] * x;
    rot[8][l] = 1.0 - b[l] * (x * x + y * y);
  }
  // F = R (U + sum w_i D_i).
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 2; ++col)
      for (int l = 0; l < L; ++l)
        out[(2 * r + col) * L + l] = rot[3 * r][l] * stretch[col][l] +
                                     rot[3 * r + 1][l] * stretch[2 + col][l] +
                                     rot[3 * r + 2][l] * stretch[4 + col][l];
  // dF/dw_i = psi_i x F (column by column) + R D_i, psi_i = J_l(phi) phi_i, because
  // d exp(phi)/dw_i = [J_l(phi) phi_i]_x exp(phi) (so3.h).
  for (int i = 0; i < k; ++i) {
    const double* f = feature + i * 9 * L;
    const double* d = f + 3 * L;
    double* o = out + (i + 1) * 6 * L;
    double psi[3][L];
    for (int l = 0; l < L; ++l) {
      const double x = phi[0][l], y = phi[1][l], z = phi[2][l];
      const double u0 = f[l], u1 = f[L + l], u2 = f[2 * L + l];
      const double c0 = y * u2 - z * u1, c1 = z * u0 - x * u2, c2 = x * u1 - y * u0;
      psi[0][l] = u0 + b[l] * c0 + c[l] * (y * c2 - z * c1);
      psi[1][l] = u1 + b[l] * c1 + c[l] * (z * c0 - x * c2);
      psi[2][l] = u2 + b[l] * c2 + c[l] * (x * c1 - y * c0);
    }
    // Row r, column col: (psi x F_col)_r + (R D)_{r,col}; the cross product's row r pairs
    // components r+1 and r+2 (cyclic).
    for (int r = 0; r < 3; ++r) {
      const int p = (r + 1) % 3, q = (r + 2) % 3;
      for (int col = 0; col < 2; ++col) {
        const double* fp = out + (2 * p + col) * L;
        const double* fq = out + (2 * q + col) * L;
        const double* d0 = d + col * L;
        const double* d1 = d + (2 + col) * L;
        const double* d2 = d + (4 + col) * L;
        double* target = o + (2 * r + col) * L;
        for (int l = 0; l < L; ++l)
          target[l] = psi[p][l] * fq[l] - psi[q][l] * fp[l] + rot[3 * r][l] * d0[l] +
                      rot[3 * r + 1][l] * d1[l] + rot[3 * r + 2][l] * d2[l];
      }
    }
  }
}

}  // namespace meshik
