// Error quadrics of every vertex in every pose (Mohr and Gleicher's deformation-sensitive
// decimation: the quadric error of a collapse summed over the poses).
#pragma once

#include <vector>

#include "../quadric.h"
#include "pose_table.h"

namespace meshik {
namespace decimation {

class PoseQuadrics {
 public:
  // triangles: #F by 3 row-major vertex ids (checked); poses: their positions; threads: >= 1.
  // Each vertex starts with, per pose, the area-weighted planes of its triangles plus planes through
  // its open border edges perpendicular to their triangle (kBoundaryPlaneWeight).
  PoseQuadrics(const int* triangles, int num_triangles, const PoseTable& poses, int threads);

  // The error of collapsing v0 onto v1: the sum over the poses of (Q_v0 + Q_v1) at v1's position
  // in that pose (>= 0).
  double collapse_error(int v0, int v1) const;
  // Adds v0's quadrics to v1's (after collapsing v0 onto v1).
  void merge(int v0, int v1);

 private:
  Quadric& at(int vertex, int pose) { return quadrics_[static_cast<size_t>(vertex) * poses_.count() + pose]; }
  const Quadric& at(int vertex, int pose) const {
    return quadrics_[static_cast<size_t>(vertex) * poses_.count() + pose];
  }

  const PoseTable& poses_;
  std::vector<Quadric> quadrics_;  // #V by #P
};

}  // namespace decimation
}  // namespace meshik
