// Vertex-major pose positions (see pose_table.h).
#include "pose_table.h"

namespace meshik {
namespace decimation {

PoseTable::PoseTable(const std::vector<const double*>& poses, int num_vertices, int threads)
    : num_poses_(static_cast<int>(poses.size())),
      num_vertices_(num_vertices),
      xyz_(3 * static_cast<size_t>(num_vertices) * poses.size()) {
  (void)threads;  // unused without OpenMP
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int v = 0; v < num_vertices; ++v)
    for (int p = 0; p < num_poses_; ++p)
      for (int k = 0; k < 3; ++k) xyz_[3 * (static_cast<size_t>(v) * num_poses_ + p) + k] = poses[p][3 * static_cast<size_t>(v) + k];
}

}  // namespace decimation
}  // namespace meshik
