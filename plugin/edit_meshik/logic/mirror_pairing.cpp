#include "mirror_pairing.h"

#include "bounding_box.h"

#include <cmath>

namespace meshik::edit {

MirrorPlane MirrorPlane::throughCentre(const std::vector<double>& vertices, int axis) {
  const BoundingBox box = boundingBox(vertices.data(), vertices.size() / 3);
  return {axis, 0.5 * (box.low[axis] + box.high[axis])};
}

MirrorPlane MirrorPlane::throughPoint(const double* point, int axis) { return {axis, point[axis]}; }

void MirrorPlane::reflect(const double* p, double* out) const {
  for (int k = 0; k < 3; ++k) out[k] = k == axis ? 2.0 * offset - p[k] : p[k];
}

int mirrorPartner(const std::vector<double>& rest, int vertex, const MirrorPlane& plane, double tolerance) {
  double image[3];
  plane.reflect(&rest[3 * static_cast<size_t>(vertex)], image);
  int best = -1;
  double best_distance = tolerance;
  for (size_t v = 0; 3 * v < rest.size(); ++v) {
    const double distance = std::hypot(rest[3 * v] - image[0], rest[3 * v + 1] - image[1], rest[3 * v + 2] - image[2]);
    if (distance <= best_distance) {
      best_distance = distance;
      best = static_cast<int>(v);
    }
  }
  return best;
}

int partnerGroup(const std::vector<int>& handles, const std::vector<int>& groups, const std::vector<int>& mirrors,
                 int handle) {
  for (size_t h = 0; h < handles.size(); ++h) {
    if (static_cast<int>(h) == handle || groups[h] != groups[handle] || mirrors[h] < 0) continue;
    for (size_t p = 0; p < handles.size(); ++p)
      if (handles[p] == mirrors[h] && groups[p] != groups[handle]) return groups[p];
  }
  return -1;
}

}  // namespace meshik::edit
