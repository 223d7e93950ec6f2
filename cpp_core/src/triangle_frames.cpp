// Rest frames, plane bases and in-plane gradient coefficients of every triangle.
#include "triangle_frames.h"

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "huge_pages.h"
#include "simd_clones.h"

namespace meshik {

namespace {

Eigen::Vector3d corner(const double* vertices, const int* triangles, int j, int q) {
  const double* p = vertices + 3 * static_cast<size_t>(triangles[3 * j + q]);
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

}  // namespace

Eigen::Vector3d fourth_vertex_offset(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  const Eigen::Vector3d n = e1.cross(e2);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / std::sqrt(length)) : Eigen::Vector3d::Zero();
}

TriangleFrames compute_triangle_frames(const double* rest, const int* triangles,
                                       int num_triangles) {
  TriangleFrames frames;
  frames.num_triangles = num_triangles;
  assign_on_huge_pages(frames.gradient, 6 * static_cast<size_t>(num_triangles), 0.0);
  assign_on_huge_pages(frames.plane_basis, 6 * static_cast<size_t>(num_triangles), 0.0);
  assign_on_huge_pages(frames.frame_inverse, 9 * static_cast<size_t>(num_triangles), 0.0);
  for (int j = 0; j < num_triangles; ++j) {
    const Eigen::Vector3d a = corner(rest, triangles, j, 0);
    const Eigen::Vector3d e1 = corner(rest, triangles, j, 1) - a;
    const Eigen::Vector3d e2 = corner(rest, triangles, j, 2) - a;
    Eigen::Matrix3d frame;
    frame << e1, e2, fourth_vertex_offset(e1, e2);
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(frames.frame_inverse.data() + 9 * j) =
        frame.inverse();

    // U = [u1 u2]: u1 along e1, u2 = normal x u1.
    const Eigen::Vector3d u1 = e1.normalized();
    const Eigen::Vector3d u2 = e1.cross(e2).normalized().cross(u1);
    Eigen::Map<Eigen::Matrix<double, 3, 2, Eigen::RowMajor>> basis(frames.plane_basis.data() + 6 * j);
    basis << u1, u2;

    // Edges in plane coordinates E = U^T [e1 e2] (upper triangular); Q(X) = [x2-x1, x3-x1] E^{-1},
    // so g_2 and g_3 are the rows of E^{-1}.
    Eigen::Matrix2d edges;
    edges << e1.dot(u1), e2.dot(u1), 0.0, e2.dot(u2);
    const Eigen::Matrix2d inverse = edges.inverse();
    double* g = frames.gradient.data() + 6 * j;
    g[2] = inverse(0, 0);
    g[3] = inverse(0, 1);
    g[4] = inverse(1, 0);
    g[5] = inverse(1, 1);
    g[0] = -(g[2] + g[4]);
    g[1] = -(g[3] + g[5]);
  }
  return frames;
}

Eigen::Matrix3d deformation_gradient(const TriangleFrames& frames, const int* triangles,
                                     const double* vertices, int j) {
  double lanes[9][kGradientLanes];
  deformation_gradients(frames, triangles, vertices, j, 1, lanes);
  Eigen::Matrix3d t;
  for (int e = 0; e < 9; ++e) t(e / 3, e % 3) = lanes[e][0];
  return t;
}

MESHIK_SIMD_CLONES
void deformation_gradients(const TriangleFrames& frames, const int* triangles, const double* vertices, int first,
                           int count, double (&t)[9][kGradientLanes]) {
  constexpr int N = kGradientLanes;
  // Deformed frame D = [e1 e2 n / sqrt|n|] (rows r, columns c: d[3 r + c]) and V^{-1}, per lane;
  // lanes past count repeat the last triangle.
  double d[9][N], inverse[9][N];
  for (int l = 0; l < N; ++l) {
    const int j = first + (l < count ? l : count - 1);
    const double* a = vertices + 3 * static_cast<size_t>(triangles[3 * j]);
    const double* b = vertices + 3 * static_cast<size_t>(triangles[3 * j + 1]);
    const double* c = vertices + 3 * static_cast<size_t>(triangles[3 * j + 2]);
    for (int r = 0; r < 3; ++r) {
      d[3 * r][l] = b[r] - a[r];
      d[3 * r + 1][l] = c[r] - a[r];
    }
    for (int e = 0; e < 9; ++e) inverse[e][l] = frames.frame_inverse[9 * static_cast<size_t>(j) + e];
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
