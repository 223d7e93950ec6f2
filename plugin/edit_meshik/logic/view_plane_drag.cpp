#include "view_plane_drag.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace meshik::edit {

ViewPlaneDrag::ViewPlaneDrag(const ScreenProjection& projection, std::vector<double> targets, int grabbed,
                             std::vector<int> group, double x, double y)
    : projection_(projection), start_targets_(std::move(targets)), grabbed_(grabbed), group_(std::move(group)) {
  if (std::find(group_.begin(), group_.end(), grabbed_) == group_.end()) group_.push_back(grabbed_);
  anchor_ = projection_.project(&start_targets_[3 * static_cast<size_t>(grabbed_)]);
  offset_x_ = anchor_.x - x;
  offset_y_ = anchor_.y - y;
}

std::vector<double> ViewPlaneDrag::targetsAt(double x, double y) const {
  std::vector<double> targets = start_targets_;
  double moved[3];
  if (!projection_.unproject({x + offset_x_, y + offset_y_, anchor_.depth}, moved)) return targets;
  const double* start = &start_targets_[3 * static_cast<size_t>(grabbed_)];
  const double delta[3] = {moved[0] - start[0], moved[1] - start[1], moved[2] - start[2]};
  for (int index : group_)
    for (int k = 0; k < 3; ++k) targets[3 * static_cast<size_t>(index) + k] += delta[k];
  return targets;
}

}  // namespace meshik::edit
