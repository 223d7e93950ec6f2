// The multi-pose distance guard as an OpenMesh decimater module (see pose_distance_module.h).
#include "pose_distance_module.h"

namespace meshik {
namespace decimation {

std::array<int, 3> OpenMeshTriangles::corners(int t) const {
  std::array<int, 3> v;
  int i = 0;
  for (auto vh : mesh_.fv_range(mesh_.face_handle(t))) v[i++] = vh.idx();
  return v;
}

std::vector<int> OpenMeshTriangles::triangles_around(int v) const {
  std::vector<int> around;
  for (auto fh : mesh_.vf_range(mesh_.vertex_handle(v))) around.push_back(fh.idx());
  return around;
}

void ModPoseDistance::configure(const Poses* poses, double max_distance) {
  poses_ = poses;
  max_distance_ = max_distance;
  if (guard_) guard_->set_bound(max_distance);
}

void ModPoseDistance::initialize() {
  guard_ = std::make_unique<DistanceGuard<OpenMeshTriangles, Poses>>(triangles_, *poses_);
  guard_->set_bound(max_distance_);
}

float ModPoseDistance::collapse_priority(const CollapseInfo& ci) {
  return guard_->allows(ci.v0.idx(), ci.v1.idx()) ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
}

}  // namespace decimation
}  // namespace meshik
