// Rigid motions of handle groups: rotations from an axis and an angle, the rotation test for
// 4 by 4 matrices, and moving a group's rest positions.
#pragma once

#include "meshik/constraints/constraint_file.h"

#include <vector>

namespace meshik::constraints {

// Row-major 3 by 3 rotation by `degrees` (right-handed) about `axis` (any non-zero, finite length).
Mat3 axis_angle_matrix(const Vec3& axis, double degrees);

// Whether a row-major 3 by 3 matrix is orthonormal with determinant +1, within 1e-5.
bool is_rotation(const Mat3& matrix);

// #P by 3 targets of a group from its #P by 3 rest positions: positions as given for a position
// list, else p -> rotation (p - center) + center + translation (center: the rest centroid when unset).
std::vector<double> group_targets(const GroupTarget& target, const std::vector<double>& rest_positions);

}  // namespace meshik::constraints
