// Decimater module that bounds, in every pose, the distance between the simplified and the original
// surface (OpenMesh's decimater): the distance_guard.h guard on an OpenMesh mesh.
// Binary: it only allows or refuses; the priority comes from another module.
#pragma once

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "decimation_mesh.h"
#include "distance_guard.h"

namespace meshik {
namespace decimation {

// DistanceGuard's view of an OpenMesh mesh decimated without garbage collection: face and vertex
// indices are the original triangle and vertex ids throughout.
class OpenMeshTriangles {
 public:
  explicit OpenMeshTriangles(const Mesh& mesh) : mesh_(mesh) {}
  int num_triangles() const { return static_cast<int>(mesh_.n_faces()); }
  bool triangle_alive(int t) const { return !mesh_.status(mesh_.face_handle(t)).deleted(); }
  // The corners of triangle t, in OpenMesh's order.
  std::array<int, 3> corners(int t) const;
  // The triangles around vertex v, in OpenMesh's order.
  std::vector<int> triangles_around(int v) const;

 private:
  const Mesh& mesh_;
};

class ModPoseDistance : public OpenMesh::Decimater::ModBaseT<Mesh> {
 public:
  typedef OpenMesh::Decimater::ModHandleT<ModPoseDistance> Handle;
  typedef OpenMesh::Decimater::ModBaseT<Mesh> Base;
  DECIMATER_MODNAME(PoseDistance)

  // DecimaterT::add constructs modules from the mesh alone: configure() sets the rest.
  explicit ModPoseDistance(Mesh& mesh) : Base(mesh, true), triangles_(mesh) {}

  // poses: every pose's positions (kept alive by the caller); max_distance: the bound (infinity:
  // never refuse, only track). Resets least_refused().
  void configure(const Poses* poses, double max_distance);

  void initialize() override;
  float collapse_priority(const CollapseInfo& ci) override;
  void preprocess_collapse(const CollapseInfo& ci) override { guard_->before_collapse(ci.v0.idx()); }
  void postprocess_collapse(const CollapseInfo& ci) override { guard_->after_collapse(ci.v1.idx()); }

  // See DistanceGuard::least_refused and worst_distance.
  double least_refused() const { return guard_->least_refused(); }
  double worst_distance() const { return guard_->worst_distance(); }

 private:
  OpenMeshTriangles triangles_;
  const Poses* poses_ = nullptr;
  double max_distance_ = std::numeric_limits<double>::infinity();
  std::unique_ptr<DistanceGuard<OpenMeshTriangles, Poses>> guard_;
};

}  // namespace decimation
}  // namespace meshik
