// The distance bound of a decimation in every pose, shared by both decimators (the fast one on
// CollapseMesh, OpenMesh's through ModPoseDistance):
//
// Every removed original vertex is attached to one live triangle, and every original triangle to
// the live triangle that covers it (at first, itself). A collapse v0 -> v1 is allowed unless, in
// some pose, (1) v0 or a vertex attached to the triangles around v0 lies farther than the bound
// from every triangle that replaces them (the same one in every pose), or (2) a sample point of a
// replacing triangle (centroid, edge midpoints, three inner points) lies farther than the bound
// from every original triangle covered by the triangles around v0. After the collapse those
// vertices and original triangles go to the triangle around v1 nearest to them.
//
// MeshT (triangle ids persist through collapses; vertex ids are the original ones):
//   int num_triangles() const; bool triangle_alive(int t) const;
//   std::array<int, 3> corners(int t) const;           the current corners of live triangle t
//   Range triangles_around(int v) const;               live triangles with corner v (ints)
// PoseSetT: int count() const; Vec at(int pose, int vertex) const, Vec with triangle_distance.h's
// operations (OpenMesh's Vec3d or Vec3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "triangle_distance.h"

namespace meshik {
namespace decimation {

// Barycentric coordinates of the points sampled on a simplified triangle.
constexpr double kDistanceSamples[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0.0},         {0.0, 0.5, 0.5},
                                           {0.5, 0.0, 0.5},             {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                           {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};

template <class MeshT, class PoseSetT>
class DistanceGuard {
 public:
  // mesh, poses: the decimation's (kept alive by the caller, mesh not yet collapsed).
  DistanceGuard(const MeshT& mesh, const PoseSetT& poses)
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

  // Sets the bound (infinity: allow everything, only track) and resets least_refused().
  void set_bound(double max_distance) {
    max_distance_ = max_distance;
    least_refused_ = kUnlimited;
  }

  // Whether collapsing v0 onto v1 keeps every measure within the bound; a refusal lowers
  // least_refused() to what this collapse would have needed (a lower bound of it).
  bool allows(int v0, int v1) {
    if (std::isinf(max_distance_)) return true;
    std::vector<std::array<int, 3>> replacing;  // the triangles around v0 after the collapse
    for (int t : mesh_.triangles_around(v0)) {
      std::array<int, 3> c = mesh_.corners(t);
      if (c[0] == v1 || c[1] == v1 || c[2] == v1) continue;  // removed by the collapse
      for (int& v : c)
        if (v == v0) v = v1;
      replacing.push_back(c);
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

  // Takes the collapse about to happen; collapse the mesh, then call after_collapse(v1).
  void before_collapse(int v0) {
    moving_.assign(1, v0);
    moving_triangles_ = covered_around(v0);
    for (int t : mesh_.triangles_around(v0)) {
      moving_.insert(moving_.end(), attached_[t].begin(), attached_[t].end());
      attached_[t].clear();
      covered_[t].clear();
    }
  }

  // Re-attaches what before_collapse took to the triangles around v1 after the collapse.
  void after_collapse(int v1) {
    for (int point : moving_) {
      int nearest = -1;
      double nearest_distance = kUnlimited;
      for (int t : mesh_.triangles_around(v1)) {
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
      const auto centroid = (poses_.at(0, o[0]) + poses_.at(0, o[1]) + poses_.at(0, o[2])) / 3.0;
      int nearest = -1;
      double nearest_distance = kUnlimited;
      for (int t : mesh_.triangles_around(v1)) {
        const std::array<int, 3> c = mesh_.corners(t);
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

  // A lower bound of the least bound under which a refused collapse would have been allowed.
  double least_refused() const { return least_refused_; }

  // The larger, over all poses, of a removed vertex's distance from its triangle and a live
  // triangle's sample points' distance from the original triangles around it; 0 when nothing moved.
  double worst_distance() const {
    double worst = 0.0, found;
    for (int t = 0; t < mesh_.num_triangles(); ++t) {
      if (!mesh_.triangle_alive(t)) continue;
      const std::array<int, 3> c = mesh_.corners(t);
      // each measure is searched only above the worst so far: a search that exceeds it returns an
      // exact distance above it (raising it), one that does not leaves it the maximum
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

 private:
  static constexpr double kUnlimited = std::numeric_limits<double>::infinity();

  // Largest distance over the poses from original vertex `point` to the triangle `c`; stops early
  // (returning a value above the limit) once a pose exceeds `limit`.
  double pose_distance(int point, const std::array<int, 3>& c, double limit) const {
    const double limit_squared = limit * limit;
    double worst = 0.0;
    for (int p = 0; p < poses_.count(); ++p) {
      worst = std::max(worst, squared_distance_to_triangle(poses_.at(p, point), poses_.at(p, c[0]),
                                                           poses_.at(p, c[1]), poses_.at(p, c[2])));
      if (worst > limit_squared) break;
    }
    return std::sqrt(worst);
  }

  // Largest distance over the sample points of triangle `c` and the poses from the nearest original
  // triangle in `covered`; stops early (above the limit) once a sample exceeds `limit`.
  double surface_gap(const std::array<int, 3>& c, const std::vector<int>& covered, double limit) const {
    const double limit_squared = limit * limit;
    const bool exact = std::isinf(limit);  // otherwise any covered triangle within the limit will do
    double worst = 0.0;
    for (const auto& w : kDistanceSamples) {
      size_t hint = 0;  // the covered triangle nearest in the previous pose is tried first
      for (int p = 0; p < poses_.count(); ++p) {
        const auto sample = w[0] * poses_.at(p, c[0]) + w[1] * poses_.at(p, c[1]) + w[2] * poses_.at(p, c[2]);
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

  // The original triangles covered by the live triangles around `vertex`.
  std::vector<int> covered_around(int vertex) const {
    std::vector<int> covered;
    for (int t : mesh_.triangles_around(vertex))
      covered.insert(covered.end(), covered_[t].begin(), covered_[t].end());
    return covered;
  }

  const MeshT& mesh_;
  const PoseSetT& poses_;
  double max_distance_ = kUnlimited;
  double least_refused_ = kUnlimited;
  std::vector<std::vector<int>> attached_;              // per triangle: removed vertices attached to it
  std::vector<std::vector<int>> covered_;               // per triangle: original triangles it covers
  std::vector<std::array<int, 3>> original_triangles_;  // #F original corners
  std::vector<int> moving_;                             // vertices being re-attached by a collapse
  std::vector<int> moving_triangles_;                   // original triangles being re-attached
};

}  // namespace decimation
}  // namespace meshik
