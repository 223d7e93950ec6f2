// Squared distance from a point to a triangle (closest point by Voronoi region of the triangle).
#pragma once

namespace meshik {
namespace decimation {

// Takes the point p and the triangle's corners a, b, c (a degenerate triangle is measured as its
// closest edge or corner); returns the squared distance from p to the nearest point of the triangle.
// Vec: OpenMesh's Vec3d or Vec3 (vec3.h): anything with -, * by a double, sqrnorm() and a dot()
// found next to it.
template <class Vec>
double squared_distance_to_triangle(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.sqrnorm();  // corner a
  const Vec bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.sqrnorm();  // corner b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (ap - ab * (d1 / (d1 - d3))).sqrnorm();  // edge ab
  const Vec cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.sqrnorm();  // corner c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (ap - ac * (d2 / (d2 - d6))).sqrnorm();  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)  // edge bc
    return (bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).sqrnorm();
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return ap.sqrnorm();  // degenerate, unreachable for a sound triangle
  return (ap - ab * (vb / sum) - ac * (vc / sum)).sqrnorm();  // interior
}

}  // namespace decimation
}  // namespace meshik
