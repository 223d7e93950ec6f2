#include "rigid_motion.h"

#include <cmath>

namespace meshik::constraints {

Mat3 axis_angle_matrix(const Vec3& axis, double degrees) {
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double x = axis[0] / length, y = axis[1] / length, z = axis[2] / length;
  const double angle = degrees * M_PI / 180.0, c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  // clang-format off
  return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y,
          t * x * y + s * z, t * y * y + c,     t * y * z - s * x,
          t * x * z - s * y, t * y * z + s * x, t * z * z + c};
  // clang-format on
}

bool is_rotation(const Mat3& r) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dot = r[i] * r[j] + r[3 + i] * r[3 + j] + r[6 + i] * r[6 + j];
      if (!(std::fabs(dot - (i == j ? 1.0 : 0.0)) <= 1e-5)) return false;
    }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
  return std::fabs(det - 1.0) <= 1e-5;
}

std::vector<double> group_targets(const GroupTarget& target, const std::vector<double>& rest_positions) {
  if (!target.rigid) return target.positions;
  const std::size_t count = rest_positions.size() / 3;
  Vec3 center{0, 0, 0};
  if (target.center) {
    center = *target.center;
  } else {
    for (std::size_t v = 0; v < count; ++v)
      for (int k = 0; k < 3; ++k) center[k] += rest_positions[3 * v + k];
    for (int k = 0; k < 3; ++k) center[k] /= static_cast<double>(count);
  }
  std::vector<double> moved(rest_positions.size());
  for (std::size_t v = 0; v < count; ++v) {
    const double d[3] = {rest_positions[3 * v] - center[0], rest_positions[3 * v + 1] - center[1],
                         rest_positions[3 * v + 2] - center[2]};
    for (int k = 0; k < 3; ++k)
      moved[3 * v + k] = target.rotation[3 * k] * d[0] + target.rotation[3 * k + 1] * d[1] +
                         target.rotation[3 * k + 2] * d[2] + center[k] + target.translation[k];
  }
  return moved;
}

}  // namespace meshik::constraints
