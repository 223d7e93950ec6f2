#include "group_rotation.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <utility>

namespace meshik::edit {

GroupRotation::GroupRotation(const ScreenProjection& projection, std::vector<double> targets, std::vector<int> group,
                             double x, double y)
    : projection_(projection), start_targets_(std::move(targets)), group_(std::move(group)), start_x_(x), start_y_(y) {
  for (int index : group_)
    for (int k = 0; k < 3; ++k) centre_[k] += start_targets_[3 * static_cast<size_t>(index) + k];
  for (double& c : centre_) c /= group_.empty() ? 1.0 : static_cast<double>(group_.size());
  centre_window_ = projection_.project(centre_.data());
  // The line of sight through the centre: from its point on the far plane to the one on the near plane.
  double near_point[3], far_point[3];
  if (projection_.unproject({centre_window_.x, centre_window_.y, 0.0}, near_point) &&
      projection_.unproject({centre_window_.x, centre_window_.y, 1.0}, far_point)) {
    double length = 0.0;
    for (int k = 0; k < 3; ++k) {
      towards_viewer_[k] = near_point[k] - far_point[k];
      length += towards_viewer_[k] * towards_viewer_[k];
    }
    length = std::sqrt(length);
    if (length > 0.0 && std::isfinite(length))
      for (double& v : towards_viewer_) v /= length;
    else
      towards_viewer_ = {0.0, 0.0, 1.0};
  } else {
    towards_viewer_ = {0.0, 0.0, 1.0};
  }
}

std::array<double, 3> GroupRotation::axisVector() const {
  switch (axis_) {
    case RotationAxis::kX: return {1.0, 0.0, 0.0};
    case RotationAxis::kY: return {0.0, 1.0, 0.0};
    case RotationAxis::kZ: return {0.0, 0.0, 1.0};
    case RotationAxis::kView: break;
  }
  return towards_viewer_;
}

double GroupRotation::dialDegrees(double x, double y) const {
  const double ax = start_x_ - centre_window_.x, ay = start_y_ - centre_window_.y;
  const double bx = x - centre_window_.x, by = y - centre_window_.y;
  if (std::hypot(ax, ay) < 3.0 || std::hypot(bx, by) < 3.0) return 0.0;
  const double swept = std::atan2(ax * by - ay * bx, ax * bx + ay * by) * 180.0 / M_PI;
  const std::array<double, 3> axis = axisVector();
  const double facing = axis[0] * towards_viewer_[0] + axis[1] * towards_viewer_[1] + axis[2] * towards_viewer_[2];
  return facing < 0.0 ? -swept : swept;
}

std::vector<double> GroupRotation::targetsTurnedBy(double degrees) const {
  std::vector<double> targets = start_targets_;
  const std::array<double, 3> axis = axisVector();
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d(axis[0], axis[1], axis[2])).toRotationMatrix();
  const Eigen::Vector3d centre(centre_[0], centre_[1], centre_[2]);
  for (int index : group_) {
    Eigen::Map<Eigen::Vector3d> p(&targets[3 * static_cast<size_t>(index)]);
    p = centre + turn * (p - centre);
  }
  return targets;
}

}  // namespace meshik::edit
