// Dragging handle targets with the mouse: the grabbed target follows the cursor in the plane
// parallel to the screen at its depth; the other targets of the group move by the same amount.
#pragma once

#include "screen_projection.h"

#include <vector>

namespace meshik::edit {

class ViewPlaneDrag {
 public:
  // projection: the view the drag happens in
  // targets:    #H by 3 row-major targets when the mouse was pressed
  // grabbed:    the index (in 0..#H-1) of the handle under the cursor
  // group:      indices of the targets that move (the grabbed one is added when missing)
  // x, y:       the window point where the mouse was pressed
  ViewPlaneDrag(const ScreenProjection& projection, std::vector<double> targets, int grabbed,
                std::vector<int> group, double x, double y);

  // The #H by 3 targets with the mouse at window point (x, y): the grabbed target is the point at
  // its press-time depth drawn where the cursor is (keeping the press-time offset between cursor
  // and target, so nothing jumps), the group's other targets moved by the same displacement, the
  // rest unchanged. Unchanged targets when the view cannot be inverted.
  std::vector<double> targetsAt(double x, double y) const;

  int grabbed() const { return grabbed_; }
  const std::vector<int>& group() const { return group_; }

 private:
  ScreenProjection projection_;
  std::vector<double> start_targets_;
  int grabbed_;
  std::vector<int> group_;
  WindowPoint anchor_;       // the grabbed target's window point at press time
  double offset_x_, offset_y_;  // anchor minus the press point
};

}  // namespace meshik::edit
