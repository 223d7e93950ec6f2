// Multi-pose distance guard for OpenMesh's decimater (see pose_distance_module.h).
#include "pose_distance_module.h"

#include <algorithm>
#include <cmath>

#include "triangle_distance.h"

namespace meshik {
namespace decimation {

namespace {

// Barycentric coordinates of the points sampled on a simplified triangle.
constexpr double kSamples[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0.0}, {0.0, 0.5, 0.5}, {0.5, 0.0, 0.5},
                                   {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};

}  // namespace

ModPoseDistance::ModPoseDistance(Mesh& mesh) : Base(mesh, true) {
  mesh.add_property(attached_);
  mesh.add_property(covered_);
}

ModPoseDistance::~ModPoseDistance() {
  mesh().remove_property(attached_);
  mesh().remove_property(covered_);
}

void ModPoseDistance::configure(const Poses* poses, double max_distance) {
  poses_ = poses;
  max_distance_ = max_distance;
  least_refused_ = std::numeric_limits<double>::infinity();
}

void ModPoseDistance::initialize() {
  const Mesh::VertexHandle none;
  original_triangles_.assign(mesh().n_faces(), {0, 0, 0});
  for (auto fh : mesh().faces()) {
    mesh().property(attached_, fh).clear();
    mesh().property(covered_, fh).assign(1, fh.idx());
    original_triangles_[fh.idx()] = corners(fh, none, none);
  }
}

std::array<int, 3> ModPoseDistance::corners(Mesh::FaceHandle face, Mesh::VertexHandle replaced,
                                            Mesh::VertexHandle by) {
  std::array<int, 3> v;
  int i = 0;
  for (auto vh : mesh().fv_range(face)) v[i++] = (vh == replaced ? by : vh).idx();
  return v;
}

double ModPoseDistance::pose_distance(int point, const std::array<int, 3>& c, double limit) const {
  const double limit_squared = limit * limit;
  double worst = 0.0;
  for (int p = 0; p < poses_->count(); ++p) {
    worst = std::max(worst, squared_distance_to_triangle(poses_->at(p, point), poses_->at(p, c[0]),
                                                         poses_->at(p, c[1]), poses_->at(p, c[2])));
    if (worst > limit_squared) break;
  }
  return std::sqrt(worst);
}

double ModPoseDistance::surface_gap(const std::array<int, 3>& c, const std::vector<int>& covered, double limit) const {
  const double limit_squared = limit * limit;
  const bool exact = std::isinf(limit);  // otherwise any covered triangle within the limit will do
  double worst = 0.0;
  for (const auto& w : kSamples) {
    size_t hint = 0;  // the covered triangle nearest in the previous pose is tried first
    for (int p = 0; p < poses_->count(); ++p) {
      const Vec sample = w[0] * poses_->at(p, c[0]) + w[1] * poses_->at(p, c[1]) + w[2] * poses_->at(p, c[2]);
      const auto distance = [&](size_t k) {
        const auto& t = original_triangles_[covered[k]];
        return squared_distance_to_triangle(sample, poses_->at(p, t[0]), poses_->at(p, t[1]), poses_->at(p, t[2]));
      };
      double nearest = covered.empty() ? std::numeric_limits<double>::infinity() : distance(hint);
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

std::vector<int> ModPoseDistance::covered_around(Mesh::VertexHandle vertex) {
  std::vector<int> covered;
  for (auto fh : mesh().vf_range(vertex)) {
    const std::vector<int>& own = mesh().property(covered_, fh);
    covered.insert(covered.end(), own.begin(), own.end());
  }
  return covered;
}

float ModPoseDistance::collapse_priority(const CollapseInfo& ci) {
  if (std::isinf(max_distance_)) return float(Base::LEGAL_COLLAPSE);
  Mesh& m = mesh();
  std::vector<std::array<int, 3>> replacing;  // the triangles around v0 after the collapse
  for (auto fh : m.vf_range(ci.v0))
    if (fh != ci.fl && fh != ci.fr) replacing.push_back(corners(fh, ci.v0, ci.v1));
  // the least bound under which `point` would pass (a lower bound of it once above the bound)
  const auto needed = [&](int point) {
    double least = std::numeric_limits<double>::infinity();
    for (const auto& triangle : replacing) {
      least = std::min(least, pose_distance(point, triangle, max_distance_));
      if (least <= max_distance_) break;
    }
    return least;
  };
  const auto refuse = [&](double least_needed) {
    least_refused_ = std::min(least_refused_, least_needed);
    return float(Base::ILLEGAL_COLLAPSE);
  };
  double need = needed(ci.v0.idx());
  if (need > max_distance_) return refuse(need);
  for (auto fh : m.vf_range(ci.v0))
    for (int point : m.property(attached_, fh))
      if ((need = needed(point)) > max_distance_) return refuse(need);
  const std::vector<int> covered = covered_around(ci.v0);
  for (const auto& triangle : replacing)
    if ((need = surface_gap(triangle, covered, max_distance_)) > max_distance_) return refuse(need);
  return float(Base::LEGAL_COLLAPSE);
}

void ModPoseDistance::preprocess_collapse(const CollapseInfo& ci) {
  Mesh& m = mesh();
  moving_.assign(1, ci.v0.idx());
  moving_triangles_ = covered_around(ci.v0);
  for (auto fh : m.vf_range(ci.v0)) {
    std::vector<int>& attached = m.property(attached_, fh);
    moving_.insert(moving_.end(), attached.begin(), attached.end());
    attached.clear();
    m.property(covered_, fh).clear();
  }
}

void ModPoseDistance::postprocess_collapse(const CollapseInfo& ci) {
  Mesh& m = mesh();
  const Mesh::VertexHandle none;
  for (int point : moving_) {
    Mesh::FaceHandle nearest;
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (auto fh : m.vf_range(ci.v1)) {
      const double distance = pose_distance(point, corners(fh, none, none), nearest_distance);
      if (distance < nearest_distance || !nearest.is_valid()) {
        nearest = fh;
        nearest_distance = distance;
      }
    }
    if (nearest.is_valid()) m.property(attached_, nearest).push_back(point);
  }
  // each original triangle goes to the remaining triangle nearest its rest centroid
  for (int original : moving_triangles_) {
    const auto& t = original_triangles_[original];
    const Vec centroid = (poses_->at(0, t[0]) + poses_->at(0, t[1]) + poses_->at(0, t[2])) / 3.0;
    Mesh::FaceHandle nearest;
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (auto fh : m.vf_range(ci.v1)) {
      const auto c = corners(fh, none, none);
      const double distance = squared_distance_to_triangle(centroid, poses_->at(0, c[0]), poses_->at(0, c[1]),
                                                           poses_->at(0, c[2]));
      if (distance < nearest_distance || !nearest.is_valid()) {
        nearest = fh;
        nearest_distance = distance;
      }
    }
    if (nearest.is_valid()) m.property(covered_, nearest).push_back(original);
  }
  moving_.clear();
  moving_triangles_.clear();
}

double ModPoseDistance::worst_distance() {
  double worst = 0.0;
  const double unlimited = std::numeric_limits<double>::infinity();
  for (auto fh : mesh().faces()) {
    const auto c = corners(fh, Mesh::VertexHandle(), Mesh::VertexHandle());
    for (int point : mesh().property(attached_, fh)) worst = std::max(worst, pose_distance(point, c, unlimited));
    const std::vector<int>& covered = mesh().property(covered_, fh);
    // an untouched original triangle covers itself (gap 0); a changed one is sampled
    if (covered.size() == 1 && original_triangles_[covered[0]] == c) continue;
    std::vector<int> nearby;  // the original triangles covered by the faces sharing a corner
    for (auto vh : mesh().fv_range(fh)) {
      const std::vector<int> around = covered_around(vh);
      nearby.insert(nearby.end(), around.begin(), around.end());
    }
    worst = std::max(worst, surface_gap(c, nearby, unlimited));
  }
  return worst;
}

}  // namespace decimation
}  // namespace meshik
