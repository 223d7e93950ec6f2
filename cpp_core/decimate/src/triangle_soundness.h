// Whether a triangle stays sound when one of its corners moves (a collapse guard shared by both
// decimators).
#pragma once

#include <algorithm>
#include <array>

namespace meshik {
namespace decimation {

// Takes a triangle's corners in one pose, which corner moves (0, 1 or 2) and where to, and the
// least cosine allowed between the triangle's normals before and after; returns whether the moved
// triangle is non-degenerate and turned by no more than that. Vec: OpenMesh's Vec3d or Vec3, with
// -, norm() and a cross() and dot() found next to it.
template <class Vec>
bool moved_triangle_is_sound(std::array<Vec, 3> corner, int moved, const Vec& target, double min_cos) {
  const Vec before = cross(corner[1] - corner[0], corner[2] - corner[0]);
  corner[moved] = target;
  const Vec after = cross(corner[1] - corner[0], corner[2] - corner[0]);
  const double before_norm = before.norm(), after_norm = after.norm();
  if (after_norm <= 1e-12 * std::max(before_norm, 1e-300)) return false;
  return dot(before, after) >= min_cos * before_norm * after_norm;
}

}  // namespace decimation
}  // namespace meshik
