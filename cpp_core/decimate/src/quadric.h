// The error quadric of Garland and Heckbert, shared by both decimators.
#pragma once

#include <array>

namespace meshik {
namespace decimation {

// Symmetric 4 by 4 error quadric: the sum of w (n.x + d)^2 over planes, stored as its 10 distinct
// entries. Vec: any 3-vector with operator[] (OpenMesh's Vec3d, Vec3).
struct Quadric {
  std::array<double, 10> q{};

  // Adds the plane n.x + d = 0 (n of unit length) with weight w.
  template <class Vec>
  void add_plane(const Vec& n, double d, double w) {
    const double a = n[0], b = n[1], c = n[2];
    const double terms[10] = {a * a, a * b, a * c, a * d, b * b, b * c, b * d, c * c, c * d, d * d};
    for (int i = 0; i < 10; ++i) q[i] += w * terms[i];
  }
  Quadric& operator+=(const Quadric& other) {
    for (int i = 0; i < 10; ++i) q[i] += other.q[i];
    return *this;
  }
  // The error x^T Q x at the point p (homogeneous coordinate 1).
  template <class Vec>
  double error(const Vec& p) const {
    const double x = p[0], y = p[1], z = p[2];
    return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z +
           2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
  }
};

// Weight of the plane through an open border edge, perpendicular to its triangle, per squared edge
// length: keeps borders in place.
constexpr double kBoundaryPlaneWeight = 10.0;

}  // namespace decimation
}  // namespace meshik
