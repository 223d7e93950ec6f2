// Rest frames, plane bases and in-plane gradient coefficients of every triangle.
#include "triangle_frames.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "page_arrays.h"
#include "simd_clones.h"
#include "thread_count.h"

namespace meshik {

Eigen::Vector3d fourth_vertex_offset(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  const Eigen::Vector3d n = e1.cross(e2);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / std::sqrt(length)) : Eigen::Vector3d::Zero();
}

namespace {

// The frames of the count (1 <= count <= kGradientLanes) triangles first, first + 1, ... (first:
// a multiple of kGradientLanes), all lanes at once, written to their rows of frames' arrays.
MESHIK_SIMD_CLONES
void frames_of_batch(const double* rest, const int* triangles, int first, int count, TriangleFrames& frames) {
  constexpr int N = kGradientLanes;
  double e1[3][N], e2[3][N];
  edge_lanes(rest, triangles, first, count, e1, e2);
  double basis[6][N], gradient[kGradientEntries][N];
  for (int l = 0; l < N; ++l) {
    // n = e1 x e2.
    const double n0 = e1[1][l] * e2[2][l] - e1[2][l] * e2[1][l];
    const double n1 = e1[2][l] * e2[0][l] - e1[0][l] * e2[2][l];
    const double n2 = e1[0][l] * e2[1][l] - e1[1][l] * e2[0][l];
    const double length = std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    const bool flat = !(length > 0.0);
    // U = [u1 u2]: u1 along e1, u2 = (n / |n|) x u1.
    const double inverse_e1 = 1.0 / std::sqrt(e1[0][l] * e1[0][l] + e1[1][l] * e1[1][l] + e1[2][l] * e1[2][l]);
    const double u1[3] = {e1[0][l] * inverse_e1, e1[1][l] * inverse_e1, e1[2][l] * inverse_e1};
    const double inverse_n = 1.0 / (flat ? 1.0 : length);
    const double m0 = n0 * inverse_n, m1 = n1 * inverse_n, m2 = n2 * inverse_n;
    const double u2[3] = {m1 * u1[2] - m2 * u1[1], m2 * u1[0] - m0 * u1[2], m0 * u1[1] - m1 * u1[0]};
    for (int r = 0; r < 3; ++r) {
      basis[2 * r][l] = u1[r];
      basis[2 * r + 1][l] = u2[r];
    }

    // Edges in plane coordinates E = U^T [e1 e2] = [p q; 0 s] (upper triangular); Q(X) =
    // [x2-x1, x3-x1] E^{-1}, so g_2 and g_3 are the rows of E^{-1} = [1/p, -q/(p s); 0, 1/s].
    const double p = e1[0][l] * u1[0] + e1[1][l] * u1[1] + e1[2][l] * u1[2];
    const double q = e2[0][l] * u1[0] + e2[1][l] * u1[1] + e2[2][l] * u1[2];
    const double s = e2[0][l] * u2[0] + e2[1][l] * u2[1] + e2[2][l] * u2[2];
    const double inverse_ps = 1.0 / (p * s);
    gradient[0][l] = s * inverse_ps;
    gradient[1][l] = -q * inverse_ps;
    gradient[2][l] = p * inverse_ps;
  }
  for (int l = 0; l < count; ++l) {
    const size_t j = static_cast<size_t>(first + l);
    for (int e = 0; e < 6; ++e) frames.plane_basis[6 * static_cast<size_t>(first) + e * N + l] = basis[e][l];
    for (int e = 0; e < kGradientEntries; ++e) frames.gradient[kGradientEntries * j + e] = gradient[e][l];
  }
}

}  // namespace

TriangleFrames compute_triangle_frames(const double* rest, const int* triangles, int num_triangles, int team) {
  TriangleFrames frames;
  frames.num_triangles = num_triangles;
  assign_by_team(frames.gradient, kGradientEntries * static_cast<size_t>(num_triangles), 0.0, team);
  const int batches = (num_triangles + kGradientLanes - 1) / kGradientLanes;
  assign_by_team(frames.plane_basis, 6 * static_cast<size_t>(batches) * kGradientLanes, 0.0, team);
  // Chunks of batches handed out as threads come free (the ExampleSet's analysis thread shares the
  // cores); each batch's values are the same whichever thread computes them.
  const int batches_per_task = dynamic_chunk(batches, team);
#pragma omp parallel for num_threads(team) schedule(dynamic, batches_per_task)
  for (int batch = 0; batch < batches; ++batch) {
    const int first = batch * kGradientLanes;
    frames_of_batch(rest, triangles, first, std::min(kGradientLanes, num_triangles - first), frames);
  }
  return frames;
}

void rest_frame_inverse(const double* gradient, const double* plane_basis, int j, double (&inverse)[9]) {
  constexpr int N = kGradientLanes;
  const double* g = gradient + kGradientEntries * static_cast<size_t>(j);
  const double* basis = plane_basis + 6 * N * static_cast<size_t>(j / N) + j % N;
  const double u1[3] = {basis[0], basis[2 * N], basis[4 * N]};
  const double u2[3] = {basis[N], basis[3 * N], basis[5 * N]};
  const double n[3] = {u1[1] * u2[2] - u1[2] * u2[1], u1[2] * u2[0] - u1[0] * u2[2], u1[0] * u2[1] - u1[1] * u2[0]};
  // E^{-1} = [g0 g1; 0 g2], so 1 / (p s) = g0 g2.
  const double normal_scale = std::sqrt(g[0] * g[2]);
  for (int c = 0; c < 3; ++c) {
    inverse[c] = g[0] * u1[c] + g[1] * u2[c];
    inverse[3 + c] = g[2] * u2[c];
    inverse[6 + c] = normal_scale * n[c];
  }
}

Eigen::Matrix3d deformation_gradient(const TriangleFrames& frames, const int* triangles,
                                     const double* vertices, int j) {
  double lanes[9][kGradientLanes];
  deformation_gradients(frames.gradient.data(), frames.plane_basis.data(), triangles, vertices, j, 1, lanes);
  Eigen::Matrix3d t;
  for (int e = 0; e < 9; ++e) t(e / 3, e % 3) = lanes[e][0];
  return t;
}

MESHIK_SIMD_CLONES
void deformation_gradients(const double* gradient, const double* plane_basis, const int* triangles,
                           const double* vertices, int first, int count, double (&t)[9][kGradientLanes]) {
  constexpr int N = kGradientLanes;
  // Deformed frame D = [e1 e2 n / sqrt|n|] (rows r, columns c: d[3 r + c]) and V^{-1}, per lane;
  // lanes past count repeat the last triangle.
  double d[9][N], inverse[9][N], e1[3][N], e2[3][N];
  edge_lanes(vertices, triangles, first, count, e1, e2);
  for (int l = 0; l < N; ++l) {
    const int j = first + (l < count ? l : count - 1);
    for (int r = 0; r < 3; ++r) {
      d[3 * r][l] = e1[r][l];
      d[3 * r + 1][l] = e2[r][l];
    }
    double triangle_inverse[9];
    rest_frame_inverse(gradient, plane_basis, j, triangle_inverse);
    for (int e = 0; e < 9; ++e) inverse[e][l] = triangle_inverse[e];
  }
  for (int l = 0; l < N; ++l) {
    const double n0 = d[3][l] * d[7][l] - d[6][l] * d[4][l];
    const double n1 = d[6][l] * d[1][l] - d[0][l] * d[7][l];
    const double n2 = d[0][l] * d[4][l] - d[3][l] * d[1][l];
    const double length = std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    const double root = std::sqrt(length);
    const bool flat = !(length > 0.0);
    d[2][l] = flat ? 0.0 : n0 / root;
    d[5][l] = flat ? 0.0 : n1 / root;
    d[8][l] = flat ? 0.0 : n2 / root;
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < N; ++l)
        t[3 * r + c][l] = d[3 * r][l] * inverse[c][l] + d[3 * r + 1][l] * inverse[3 + c][l] +
                          d[3 * r + 2][l] * inverse[6 + c][l];
}

}  // namespace meshik
