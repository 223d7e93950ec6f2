// Whether a handle group's targets are a rigid motion of its rest positions (so the constraint
// file can say "rotate"/"translate" instead of listing positions), found by the SVD fit of
// Kabsch (Eigen) and checked point by point.
#pragma once

#include <array>
#include <cstddef>
#include <optional>

namespace meshik::edit {

// p -> rotation (p - center) + center + translation.
struct RigidMotion {
  std::array<double, 9> rotation;     // row-major, determinant +1
  std::array<double, 3> center;       // the centroid of the points it was fitted from
  std::array<double, 3> translation;  // the centroid's move
};

// The rigid motion taking the `count` points `from` (#count by 3 row-major) to the points `to`
// (the same shape), when it takes every point there within `tolerance` (a distance); none when
// count is 0 or the points are not moved rigidly.
std::optional<RigidMotion> fitRigidMotion(const double* from, const double* to, std::size_t count, double tolerance);

}  // namespace meshik::edit
