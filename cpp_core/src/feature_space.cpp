// Precomputation of the examples' per-triangle features (polar decomposition, rotation logs with
// consistent branches, stretches projected on the rest planes).
#include "feature_space.h"

#include "rotation_branches.h"

namespace meshik {

ExampleFeatures compute_example_features(const TriangleFrames& frames,
                                         const TriangleAdjacency& adjacency, const int* triangles,
                                         const std::vector<const double*>& examples,
                                         const ProgressCallback& progress,
                                         bool consistent_branches) {
  using Matrix32 = Eigen::Matrix<double, 3, 2, Eigen::RowMajor>;
  const int m = frames.num_triangles;
  const int k = static_cast<int>(examples.size());
  ExampleFeatures features;
  features.num_examples = k;
  features.num_triangles = m;
  features.plane_basis = frames.plane_basis;
  features.nonlinear.resize(9 * static_cast<size_t>(m) * k);
  features.linear.resize(6 * static_cast<size_t>(m) * k);

  std::vector<Eigen::Vector3d> logs(m);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < m; ++j) {
      const Eigen::Matrix3d t = deformation_gradient(frames, triangles, examples[i], j);
      const PolarDecomposition polar = polar_decomposition(t);
      logs[j] = so3_log(polar.rotation);
      const auto basis = plane_basis_of(frames, j);
      const size_t slot = static_cast<size_t>(j) * k + i;
      Eigen::Map<Matrix32>(features.nonlinear.data() + 9 * slot + 3) =
          (polar.stretch - Eigen::Matrix3d::Identity()) * basis;
      Eigen::Map<Matrix32>(features.linear.data() + 6 * slot) =
          (t - Eigen::Matrix3d::Identity()) * basis;
    }
    if (consistent_branches) choose_consistent_log_branches(adjacency, logs);
    for (int j = 0; j < m; ++j)
      Eigen::Map<Eigen::Vector3d>(features.nonlinear.data() + 9 * (static_cast<size_t>(j) * k + i)) =
          logs[j];
    if (progress && !progress(static_cast<double>(i + 1) / k, "example features"))
      throw Cancelled("cancelled while computing the features of example " + std::to_string(i));
  }
  return features;
}

}  // namespace meshik
