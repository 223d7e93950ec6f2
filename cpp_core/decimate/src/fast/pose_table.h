// Every pose's vertex positions stored vertex by vertex, so that the decimator's per-vertex loops
// over the poses read contiguous memory.
#pragma once

#include <cstddef>
#include <vector>

#include "../vec3.h"

namespace meshik {
namespace decimation {

class PoseTable {
 public:
  // poses: #P pointers to #V by 3 row-major arrays (rest first); threads: >= 1 (OpenMP threads).
  PoseTable(const std::vector<const double*>& poses, int num_vertices, int threads);

  // Position of original vertex `vertex` in pose `pose`.
  Vec3 at(int pose, int vertex) const {
    const double* p = xyz_.data() + 3 * (static_cast<size_t>(vertex) * num_poses_ + pose);
    return Vec3(p[0], p[1], p[2]);
  }
  int count() const { return num_poses_; }
  int num_vertices() const { return num_vertices_; }

 private:
  int num_poses_;
  int num_vertices_;
  std::vector<double> xyz_;  // #V by #P by 3
};

}  // namespace decimation
}  // namespace meshik
