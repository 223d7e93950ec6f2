// The map from a mesh's coordinates to window pixels that OpenGL applies when it draws the mesh
// (projection * modelview * mesh transform, then the viewport), and its inverse. Plain doubles:
// no GL calls here, so picking and dragging can be tested on a known projection.
#pragma once

#include <array>

namespace meshik::edit {

// A point in window coordinates: x, y in GL pixels (origin bottom-left), depth in [0, 1]
// (0 on the near plane, 1 on the far plane), as glReadPixels(GL_DEPTH_COMPONENT) reports it.
struct WindowPoint {
  double x = 0.0;
  double y = 0.0;
  double depth = 0.0;
};

class ScreenProjection {
 public:
  // The identity map onto a 2 by 2 viewport at the origin (a placeholder until a real one is set).
  ScreenProjection();

  // projection, modelview: 16 doubles each, column-major as glGetDoublev returns them;
  // viewport: x, y, width, height as glGetIntegerv(GL_VIEWPORT) returns them.
  ScreenProjection(const double* projection, const double* modelview, const int* viewport);

  // Window coordinates of the mesh-space point p (3 doubles).
  WindowPoint project(const double* p) const;

  // The mesh-space point (3 doubles written to `out`) drawn at window point w.
  // Returns false (and leaves `out` alone) when the map cannot be inverted there.
  bool unproject(const WindowPoint& w, double* out) const;

  // The modelview it was made with (mesh to eye coordinates, column-major; identity by default).
  const std::array<double, 16>& modelview() const { return modelview_; }

 private:
  std::array<double, 16> modelview_;
  std::array<double, 16> matrix_;   // projection * modelview, column-major
  std::array<double, 16> inverse_;  // its inverse, column-major (zero when singular)
  std::array<double, 4> viewport_;  // x, y, width, height
};

}  // namespace meshik::edit
