// A 3-vector of doubles for the OpenMesh-free decimator, with the operations triangle_distance.h
// and quadric.h use (the same names as OpenMesh's VectorT: dot, cross, sqrnorm, norm, operator[]).
#pragma once

#include <cmath>

namespace meshik {
namespace decimation {

struct Vec3 {
  double x[3] = {0.0, 0.0, 0.0};

  Vec3() = default;
  Vec3(double a, double b, double c) : x{a, b, c} {}
  double operator[](int i) const { return x[i]; }
  Vec3 operator+(const Vec3& o) const { return Vec3(x[0] + o.x[0], x[1] + o.x[1], x[2] + o.x[2]); }
  Vec3 operator-(const Vec3& o) const { return Vec3(x[0] - o.x[0], x[1] - o.x[1], x[2] - o.x[2]); }
  Vec3 operator*(double s) const { return Vec3(x[0] * s, x[1] * s, x[2] * s); }
  Vec3 operator/(double s) const { return Vec3(x[0] / s, x[1] / s, x[2] / s); }
  double sqrnorm() const { return x[0] * x[0] + x[1] * x[1] + x[2] * x[2]; }
  double norm() const { return std::sqrt(sqrnorm()); }
};

inline Vec3 operator*(double s, const Vec3& v) { return v * s; }
// Takes two vectors; returns their dot product.
inline double dot(const Vec3& a, const Vec3& b) { return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2]; }
// Takes two vectors; returns their cross product a x b.
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return Vec3(a.x[1] * b.x[2] - a.x[2] * b.x[1], a.x[2] * b.x[0] - a.x[0] * b.x[2], a.x[0] * b.x[1] - a.x[1] * b.x[0]);
}

}  // namespace decimation
}  // namespace meshik
