// Decimater module that bounds, in every pose, the distance of the removed vertices from the
// simplified surface (a multi-pose Hausdorff-style guard for OpenMesh's decimater).
//
// Both ways: every removed original vertex is attached to one remaining triangle, and every
// original triangle to the remaining triangle that covers it (at first, itself). A collapse
// v0 -> v1 is refused unless, in every pose, (1) v0 and every vertex attached to the triangles
// around v0 lie within the bound of one of the triangles that replace them (the same one in every
// pose), and (2) sample points of each replacing triangle (centroid, edge midpoints, three inner
// points) lie within the bound of an original triangle covered by the triangles around v0. After
// the collapse those vertices and original triangles are attached to the triangle around v1
// nearest to them.
// Binary: it only allows or refuses; the priority comes from another module.
#pragma once

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <array>
#include <limits>
#include <vector>

#include "decimation_mesh.h"

namespace meshik {
namespace decimation {

class ModPoseDistance : public OpenMesh::Decimater::ModBaseT<Mesh> {
 public:
  typedef OpenMesh::Decimater::ModHandleT<ModPoseDistance> Handle;
  typedef OpenMesh::Decimater::ModBaseT<Mesh> Base;
  DECIMATER_MODNAME(PoseDistance)

  // DecimaterT::add constructs modules from the mesh alone: configure() sets the rest.
  explicit ModPoseDistance(Mesh& mesh);
  ~ModPoseDistance() override;

  // poses: every pose's positions (kept alive by the caller); max_distance: the bound (infinity:
  // never refuse, only track). Resets least_refused().
  void configure(const Poses* poses, double max_distance);

  void initialize() override;
  float collapse_priority(const CollapseInfo& ci) override;
  void preprocess_collapse(const CollapseInfo& ci) override;
  void postprocess_collapse(const CollapseInfo& ci) override;

  // A lower bound of the least bound under which a collapse refused since configure() would have
  // been allowed (infinity if none was refused).
  double least_refused() const { return least_refused_; }

  // The larger, over all poses, of: the distance of a removed vertex from the triangle it is
  // attached to, and the distance of a sample point of a remaining triangle from the original
  // triangles it covers (the measures the bound applies to); 0 when nothing was removed.
  double worst_distance();

 private:
  // The three original vertex ids of face `face`, with `replaced` (if a corner) swapped for `by`.
  std::array<int, 3> corners(Mesh::FaceHandle face, Mesh::VertexHandle replaced, Mesh::VertexHandle by);
  // Largest distance over the poses from original vertex `point` to the triangle `corners`; stops
  // early (returning a value above the limit) once a pose exceeds `limit`.
  double pose_distance(int point, const std::array<int, 3>& corners, double limit) const;
  // Largest distance, over the sample points of the triangle `corners` and the poses, from the
  // nearest original triangle in `covered` (ids into original_triangles_); stops early (returning
  // a value above the limit) once a sample exceeds `limit`.
  double surface_gap(const std::array<int, 3>& corners, const std::vector<int>& covered, double limit) const;
  // The original triangles covered by the faces around `vertex`.
  std::vector<int> covered_around(Mesh::VertexHandle vertex);

  const Poses* poses_ = nullptr;
  double max_distance_ = std::numeric_limits<double>::infinity();
  double least_refused_ = std::numeric_limits<double>::infinity();
  OpenMesh::FPropHandleT<std::vector<int>> attached_;  // per face: removed vertices attached to it
  OpenMesh::FPropHandleT<std::vector<int>> covered_;   // per face: original triangles it covers
  std::vector<std::array<int, 3>> original_triangles_;  // #F original vertex ids of each triangle
  std::vector<int> moving_;                            // vertices being re-attached by a collapse
  std::vector<int> moving_triangles_;                  // original triangles being re-attached
};

}  // namespace decimation
}  // namespace meshik
