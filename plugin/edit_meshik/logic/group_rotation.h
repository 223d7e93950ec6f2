// Turning a handle group about its centre with the mouse (a dial around the centre's window
// point) or by typed degrees, about the view axis or a locked world axis X, Y or Z, as
// MeshLab's edit_manipulators does for whole layers. Plain doubles, no GL: tested on a known view.
#pragma once

#include "screen_projection.h"

#include <array>
#include <vector>

namespace meshik::edit {

// The axis a rotation turns about: the line of sight through the group's centre, or a world axis.
enum class RotationAxis { kView, kX, kY, kZ };

class GroupRotation {
 public:
  // projection: the view the rotation happens in
  // targets:    #H by 3 row-major targets when the rotation began
  // group:      indices (in 0..#H-1) of the targets that turn; the centre is their centroid
  // x, y:       the window point where the dial starts (the mouse when the rotation began)
  GroupRotation(const ScreenProjection& projection, std::vector<double> targets, std::vector<int> group, double x,
                double y);

  void setAxis(RotationAxis axis) { axis_ = axis; }
  RotationAxis axis() const { return axis_; }

  // The unit axis (3 doubles) the rotation turns about, in mesh coordinates: towards the viewer
  // for kView, else the world axis itself.
  std::array<double, 3> axisVector() const;

  // The degrees about axisVector() that a dial turned from the start point to window point (x, y)
  // means: the screen angle swept around the centre's window point, counter-clockwise positive
  // as seen by the viewer, so the group follows the cursor; its sign flips for a locked axis
  // that points away from the viewer. 0 while the cursor is within 3 pixels of the centre.
  double dialDegrees(double x, double y) const;

  // The #H by 3 targets with the group turned by `degrees` about axisVector() through the centre
  // (right-handed), the other targets unchanged.
  std::vector<double> targetsTurnedBy(double degrees) const;

  const std::array<double, 3>& centre() const { return centre_; }
  const std::vector<int>& group() const { return group_; }

 private:
  ScreenProjection projection_;
  std::vector<double> start_targets_;
  std::vector<int> group_;
  std::array<double, 3> centre_{};
  std::array<double, 3> towards_viewer_{};  // unit
  WindowPoint centre_window_;
  double start_x_, start_y_;
  RotationAxis axis_ = RotationAxis::kView;
};

}  // namespace meshik::edit
