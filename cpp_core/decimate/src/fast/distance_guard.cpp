// The fast decimator's distance bound in every pose (see distance_guard.h).
#include "distance_guard.h"

#include <algorithm>
#include <cmath>

#include "../triangle_distance.h"

namespace meshik {
namespace decimation {

namespace {

// Barycentric coordinates of the points sampled on a simplified triangle.
constexpr double kSamples[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0.0}, {0.0, 0.5, 0.5}, {0.5, 0.0, 0.5},
                                   {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};
constexpr double kUnlimited = std::numeric_limits<double>::infinity();

}  // namespace

DistanceGuard::DistanceGuard(const CollapseMesh& mesh, const PoseTable& poses)
    : mesh_(mesh),
      poses_(poses),
      attached_(mesh.num_triangles()),
      covered_(mesh.num_triangles()),
      original_triangles_(mesh.num_triangles()) {
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    covered_[t].assign(1, t);
    original_triangles_[t] = mesh.corners(t);
  }
}

void DistanceGuard::set_bound(double max_distance) {
  max_distance_ = max_distance;
  least_refused_ = kUnlimited;
}

std::array<int, 3> DistanceGuard::corners(int t, int replaced, int by) const {
  std::array<int, 3> c = mesh_.corners(t);
  for (int& v : c)
    if (v == replaced) v = by;
  return c;
}

double DistanceGuard::pose_distance(int point, const std::array<int, 3>& c, double limit) const {
  const double limit_squared = limit * limit;
  double worst = 0.0;
  for (int p = 0; p < poses_.count(); ++p) {
    worst = std::max(worst, squared_distance_to_triangle(poses_.at(p, point), poses_.at(p, c[0]), poses_.at(p, c[1]),
                                                         poses_.at(p, c[2])));
    if (worst > limit_squared) break;
  }
  return std::sqrt(worst);
}

double DistanceGuard::surface_gap(const std::array<int, 3>& c, const std::vector<int>& covered, double limit) const {
  const double limit_squared = limit * limit;
  const bool exact = std::isinf(limit);  // otherwise any covered triangle within the limit will do
  double worst = 0.0;
  for (const auto& w : kSamples) {
    size_t hint = 0;  // the covered triangle nearest in the previous pose is tried first
    for (int p = 0; p < poses_.count(); ++p) {
      const Vec3 sample = w[0] * poses_.at(p, c[0]) + w[1] * poses_.at(p, c[1]) + w[2] * poses_.at(p, c[2]);
      const auto distance = [&](size_t k) {
        const auto& t = original_triangles_[covered[k]];
        return squared_distance_to_triangle(sample, poses_.at(p, t[0]), poses_.at(p, t[1]), poses_.at(p, t[2]));
      };
      double nearest = covered.empty() ? kUnlimited : distance(hint);
      for (size_t k = 0; k < covered.size() && (exact || nearest > limit_squared); ++k) {
        const double d = distance(k);
        if (d < nearest) {
          nearest = d;
          hint = k;
        }
      }
      worst = std::max(worst, nearest);
      if (worst > limit_squared) return std::sqrt(worst);
    }
  }
  return std::sqrt(worst);
}

std::vector<int> DistanceGuard::covered_around(int vertex) const {
  std::vector<int> covered;
  for (int t : mesh_.triangles_around(vertex)) covered.insert(covered.end(), covered_[t].begin(), covered_[t].end());
  return covered;
}

bool DistanceGuard::allows(int v0, int v1) {
  if (std::isinf(max_distance_)) return true;
  std::vector<std::array<int, 3>> replacing;  // the triangles around v0 after the collapse
  for (int t : mesh_.triangles_around(v0)) {
    const std::array<int, 3>& c = mesh_.corners(t);
    if (c[0] != v1 && c[1] != v1 && c[2] != v1) replacing.push_back(corners(t, v0, v1));
  }
  // the least bound under which `point` would pass (a lower bound of it once above the bound)
  const auto needed = [&](int point) {
    double least = kUnlimited;
    for (const auto& triangle : replacing) {
      least = std::min(least, pose_distance(point, triangle, max_distance_));
      if (least <= max_distance_) break;
    }
    return least;
  };
  const auto refuse = [&](double least_needed) {
    least_refused_ = std::min(least_refused_, least_needed);
    return false;
  };
  double need = needed(v0);
  if (need > max_distance_) return refuse(need);
  for (int t : mesh_.triangles_around(v0))
    for (int point : attached_[t])
      if ((need = needed(point)) > max_distance_) return refuse(need);
  const std::vector<int> covered = covered_around(v0);
  for (const auto& triangle : replacing)
    if ((need = surface_gap(triangle, covered, max_distance_)) > max_distance_) return refuse(need);
  return true;
}

void DistanceGuard::before_collapse(int v0) {
  moving_.assign(1, v0);
  moving_triangles_ = covered_around(v0);
  for (int t : mesh_.triangles_around(v0)) {
    moving_.insert(moving_.end(), attached_[t].begin(), attached_[t].end());
    attached_[t].clear();
    covered_[t].clear();
  }
}

void DistanceGuard::after_collapse(int v1) {
  const std::vector<int>& around = mesh_.triangles_around(v1);
  for (int point : moving_) {
    int nearest = -1;
    double nearest_distance = kUnlimited;
    for (int t : around) {
      const double distance = pose_distance(point, mesh_.corners(t), nearest_distance);
      if (distance < nearest_distance || nearest < 0) {
        nearest = t;
        nearest_distance = distance;
      }
    }
    if (nearest >= 0) attached_[nearest].push_back(point);
  }
  // each original triangle goes to the live triangle nearest its rest centroid
  for (int original : moving_triangles_) {
    const auto& o = original_triangles_[original];
    const Vec3 centroid = (poses_.at(0, o[0]) + poses_.at(0, o[1]) + poses_.at(0, o[2])) * (1.0 / 3.0);
    int nearest = -1;
    double nearest_distance = kUnlimited;
    for (int t : around) {
      const auto& c = mesh_.corners(t);
      const double distance =
          squared_distance_to_triangle(centroid, poses_.at(0, c[0]), poses_.at(0, c[1]), poses_.at(0, c[2]));
      if (distance < nearest_distance || nearest < 0) {
        nearest = t;
        nearest_distance = distance;
      }
    }
    if (nearest >= 0) covered_[nearest].push_back(original);
  }
  moving_.clear();
  moving_triangles_.clear();
}

double DistanceGuard::worst_distance() const {
  double worst = 0.0;
  for (int t = 0; t < mesh_.num_triangles(); ++t) {
    if (!mesh_.triangle_alive(t)) continue;
    const auto& c = mesh_.corners(t);
    // each measure is searched only above the worst so far: a search that exceeds it returns an
    // exact distance above it (raising it), one that does not leaves it the maximum
    double found;
    for (int point : attached_[t])
      while ((found = pose_distance(point, c, worst)) > worst) worst = found;
    // an untouched original triangle covers itself (gap 0); a changed one is sampled
    if (covered_[t].size() == 1 && original_triangles_[covered_[t][0]] == c) continue;
    std::vector<int> nearby;  // the original triangles covered by the triangles sharing a corner
    for (int v : c) {
      const std::vector<int> around = covered_around(v);
      nearby.insert(nearby.end(), around.begin(), around.end());
    }
    while ((found = surface_gap(c, nearby, worst)) > worst) worst = found;
  }
  return worst;
}

}  // namespace decimation
}  // namespace meshik
