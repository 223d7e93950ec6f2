// The error quadric of Garland and Heckbert, shared by both decimators.
#pragma once

#include <array>
#include <initializer_list>

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

// Takes a triangle's corners a, b, c in one pose and the quadrics of those corners (qa, qb, qc);
// adds the triangle's plane to each, weighted by its area (nothing for a degenerate triangle).
// Vec: as Quadric's, with -, / by a double, norm() and a cross() and dot() found next to it.
template <class Vec>
void add_triangle_plane(const Vec& a, const Vec& b, const Vec& c, Quadric& qa, Quadric& qb, Quadric& qc) {
  const Vec normal = cross(b - a, c - a);
  const double twice_area = normal.norm();
  if (twice_area <= 0.0) return;
  const Vec unit = normal / twice_area;
  const double d = -dot(unit, a);
  for (Quadric* q : {&qa, &qb, &qc}) q->add_plane(unit, d, 0.5 * twice_area);
}

// Takes an open border edge from -> to, the corners a, b, c of its triangle (one pose) and the
// quadrics of the edge's ends; adds to both the plane through the edge perpendicular to the
// triangle, weighted by kBoundaryPlaneWeight times the squared edge length (nothing when the
// triangle is degenerate). Vec: as add_triangle_plane's.
template <class Vec>
void add_border_plane(const Vec& from, const Vec& to, const Vec& a, const Vec& b, const Vec& c, Quadric& q_from,
                      Quadric& q_to) {
  const Vec along = to - from;
  const Vec side = cross(along, cross(b - a, c - a));
  const double length = side.norm();
  if (length <= 0.0) return;
  const Vec unit = side / length;
  const double d = -dot(unit, from);
  const double weight = kBoundaryPlaneWeight * along.sqrnorm();
  q_from.add_plane(unit, d, weight);
  q_to.add_plane(unit, d, weight);
}

}  // namespace decimation
}  // namespace meshik
