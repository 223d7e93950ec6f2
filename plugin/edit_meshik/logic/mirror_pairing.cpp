#include "mirror_pairing.h"

#include "bounding_box.h"

#include <cmath>

namespace meshik::edit {

namespace {

double dot(const Direction& n, const double* p) { return n[0] * p[0] + n[1] * p[1] + n[2] * p[2]; }

}  // namespace

Direction axisNormal(int axis) {
  Direction normal{0.0, 0.0, 0.0};
  normal[axis] = 1.0;
  return normal;
}

Direction viewVerticalNormal(const std::array<double, 16>& modelview) {
  const Direction row{modelview[0], modelview[4], modelview[8]};  // column-major: row 0 of the 3x3 part
  const double length = std::sqrt(dot(row, row.data()));
  if (!(length > 0.0) || !std::isfinite(length)) return axisNormal(0);
  return {row[0] / length, row[1] / length, row[2] / length};
}

MirrorPlane MirrorPlane::throughCentre(const std::vector<double>& vertices, const Direction& normal) {
  const BoundingBox box = boundingBox(vertices.data(), vertices.size() / 3);
  const double centre[3] = {0.5 * (box.low[0] + box.high[0]), 0.5 * (box.low[1] + box.high[1]),
                            0.5 * (box.low[2] + box.high[2])};
  return throughPoint(centre, normal);
}

MirrorPlane MirrorPlane::throughPoint(const double* point, const Direction& normal) {
  return {normal, dot(normal, point)};
}

void MirrorPlane::reflect(const double* p, double* out) const {
  const double twice_distance = 2.0 * (dot(normal, p) - offset);
  for (int k = 0; k < 3; ++k) out[k] = p[k] - twice_distance * normal[k];
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
