// The distance bound of the fast decimator, in every pose (the same measure as the OpenMesh
// decimator's ModPoseDistance, on CollapseMesh):
//
// Every removed original vertex is attached to one live triangle, and every original triangle to
// the live triangle that covers it (at first, itself). A collapse v0 -> v1 is allowed unless, in
// some pose, (1) v0 or a vertex attached to the triangles around v0 lies farther than the bound
// from every triangle that replaces them (the same one in every pose), or (2) a sample point of a
// replacing triangle (centroid, edge midpoints, three inner points) lies farther than the bound
// from every original triangle covered by the triangles around v0. After the collapse those
// vertices and original triangles go to the triangle around v1 nearest to them.
#pragma once

#include <array>
#include <limits>
#include <vector>

#include "collapse_mesh.h"
#include "pose_table.h"

namespace meshik {
namespace decimation {

class DistanceGuard {
 public:
  // mesh, poses: the decimation's (kept alive by the caller, mesh not yet collapsed).
  DistanceGuard(const CollapseMesh& mesh, const PoseTable& poses);

  // Sets the bound (infinity: allow everything, only track) and resets least_refused().
  void set_bound(double max_distance);
  // Whether collapsing v0 onto v1 keeps every measure within the bound; a refusal lowers
  // least_refused() to what this collapse would have needed (a lower bound of it).
  bool allows(int v0, int v1);
  // Takes the collapse about to happen; call collapse() on the mesh, then after_collapse(v1).
  void before_collapse(int v0);
  void after_collapse(int v1);

  // A lower bound of the least bound under which a refused collapse would have been allowed.
  double least_refused() const { return least_refused_; }
  // The larger, over all poses, of a removed vertex's distance from its triangle and a live
  // triangle's sample points' distance from the original triangles it covers; 0 when nothing moved.
  double worst_distance() const;

 private:
  // The corners of live triangle t with `replaced` (if a corner) swapped for `by`.
  std::array<int, 3> corners(int t, int replaced, int by) const;
  // Largest distance over the poses from original vertex `point` to the triangle `c`; stops early
  // (returning a value above the limit) once a pose exceeds `limit`.
  double pose_distance(int point, const std::array<int, 3>& c, double limit) const;
  // Largest distance over the sample points of triangle `c` and the poses from the nearest original
  // triangle in `covered`; stops early (above the limit) once a sample exceeds `limit`.
  double surface_gap(const std::array<int, 3>& c, const std::vector<int>& covered, double limit) const;
  // The original triangles covered by the live triangles around `vertex`.
  std::vector<int> covered_around(int vertex) const;

  const CollapseMesh& mesh_;
  const PoseTable& poses_;
  double max_distance_ = std::numeric_limits<double>::infinity();
  double least_refused_ = std::numeric_limits<double>::infinity();
  std::vector<std::vector<int>> attached_;              // per triangle: removed vertices attached to it
  std::vector<std::vector<int>> covered_;               // per triangle: original triangles it covers
  std::vector<std::array<int, 3>> original_triangles_;  // #F original corners
  std::vector<int> moving_;                             // vertices being re-attached by a collapse
  std::vector<int> moving_triangles_;                   // original triangles being re-attached
};

}  // namespace decimation
}  // namespace meshik
