#include "vertex_picking.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace meshik::edit {
namespace {

double squaredPixelDistance(const WindowPoint& w, double x, double y) {
  return (w.x - x) * (w.x - x) + (w.y - y) * (w.y - y);
}

}  // namespace

int pickVertex(const ScreenProjection& projection, const std::vector<double>& vertices, double x, double y,
               double surface_depth, double radius) {
  if (!(surface_depth < 1.0)) return -1;
  double surface[3];
  if (!projection.unproject({x, y, surface_depth}, surface)) return -1;
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  const int count = static_cast<int>(vertices.size() / 3);
  for (int i = 0; i < count; ++i) {
    const double* p = &vertices[3 * static_cast<size_t>(i)];
    const WindowPoint w = projection.project(p);
    if (!(w.depth >= 0.0 && w.depth <= 1.0) || squaredPixelDistance(w, x, y) > radius * radius) continue;
    const double distance = (p[0] - surface[0]) * (p[0] - surface[0]) + (p[1] - surface[1]) * (p[1] - surface[1]) +
                            (p[2] - surface[2]) * (p[2] - surface[2]);
    if (distance < best_distance) {
      best_distance = distance;
      best = i;
    }
  }
  return best;
}

int pickHandle(const ScreenProjection& projection, const std::vector<double>& points, double x, double y,
               double radius) {
  int best = -1;
  double best_distance = radius * radius;
  double best_depth = std::numeric_limits<double>::infinity();
  const int count = static_cast<int>(points.size() / 3);
  for (int i = 0; i < count; ++i) {
    const WindowPoint w = projection.project(&points[3 * static_cast<size_t>(i)]);
    if (!(w.depth >= 0.0 && w.depth <= 1.0)) continue;
    const double distance = squaredPixelDistance(w, x, y);
    if (distance < best_distance || (distance == best_distance && best >= 0 && w.depth < best_depth)) {
      best = i;
      best_distance = distance;
      best_depth = w.depth;
    }
  }
  return best;
}

std::vector<int> pickVerticesInRectangle(const ScreenProjection& projection, const std::vector<double>& vertices,
                                         double x0, double y0, double x1, double y1,
                                         const std::function<double(int, int)>& surface_depth, double tolerance) {
  const double left = std::min(x0, x1), right = std::max(x0, x1), bottom = std::min(y0, y1), top = std::max(y0, y1);
  std::vector<int> inside;
  const int count = static_cast<int>(vertices.size() / 3);
  for (int i = 0; i < count; ++i) {
    const double* p = &vertices[3 * static_cast<size_t>(i)];
    const WindowPoint w = projection.project(p);
    if (!(w.depth >= 0.0 && w.depth <= 1.0) || w.x < left || w.x > right || w.y < bottom || w.y > top) continue;
    const double depth = surface_depth(static_cast<int>(std::floor(w.x)), static_cast<int>(std::floor(w.y)));
    double surface[3];
    if (!(depth < 1.0) || !projection.unproject({w.x, w.y, depth}, surface)) continue;
    if (std::hypot(p[0] - surface[0], p[1] - surface[1], p[2] - surface[2]) <= tolerance) inside.push_back(i);
  }
  return inside;
}

}  // namespace meshik::edit
