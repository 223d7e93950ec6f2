// One linear-space evaluation per handle set, then the optimal linear weights of any targets.
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 reductions (built with
// -march=native); the values it names are always written first.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "linear_start.h"

#include <vector>

#include "feature_space.h"
#include "pose_evaluation.h"
#include "trust_region.h"

namespace meshik {

LinearStartAssembly assemble_linear_start(const ExampleSet::Impl& set, const PoseSystem& system,
                                          EvaluationBuffers& buffers, int team) {
  LinearStartAssembly out;
  const int k = set.num_examples;
  if (k == 0) return out;
  out.origin.assign(3 * system.handles().size(), 0.0);
  out.evaluator = std::make_unique<PoseEvaluator>(set, system, FeatureSpace::kLinear, 0.0, out.origin.data(),
                                                  buffers, team);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(k);
  out.evaluator->assemble_system(zero.data());
  return out;
}

LinearStart::LinearStart(const ExampleSet::Impl& set, const PoseSystem& system, LinearStartAssembly assembly,
                         int team) {
  const int k = set.num_examples;
  const int num_handles = static_cast<int>(system.handles().size());
  schur_ = Eigen::MatrixXd::Zero(k, k);
  rest_gradient_ = Eigen::VectorXd::Zero(k);
  affine_ = Eigen::MatrixXd::Zero(3 * num_handles, k);
  if (k == 0) return;

  // All handles at the origin: the Gauss-Newton system gives S and g_U, then Z = K'^{-1} G'^T L
  // on the unknowns coupled to a handle (the backward solve along their tree paths only).
  PoseEvaluator& evaluator = *assembly.evaluator;
  evaluator.set_team(team);
  PoseEvaluation at_rest;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(k);
  evaluator.solve_assembled_system(zero.data(), at_rest);
  schur_ = at_rest.schur;
  rest_gradient_ = at_rest.step_rhs;
  evaluator.solve_jacobian_rows(system.coupling_row());

  // -Z^T K_fh x_h: only the rows of Z coupled to a handle.
  for (int h = 0; h < num_handles; ++h)
    for (int s = system.coupling_start()[h]; s < system.coupling_start()[h + 1]; ++s)
      for (int c = 0; c < 3; ++c) {
        const double* z = evaluator.jacobian_solution(system.coupling_row()[s], c);
        for (int i = 0; i < k; ++i) affine_(3 * h + c, i) -= system.coupling_value()[s] * z[i];
      }
  // + L^T (handles' part of Q): handle h at corner q of triangle j adds x_h . (L_ij g_q).
  for (int j : system.handle_triangles()) {
    double g[6];
    corner_gradients(set.frames.gradient.data() + kGradientEntries * static_cast<size_t>(j), g);
    for (int i = 0; i < k; ++i) {
      double linear[6 * kLanes];
      linear_features_of_batch(set.features, j / kLanes, i, linear);
      const double* l = linear + j % kLanes;
      for (int q = 0; q < 3; ++q) {
        const int h = system.handle_of_vertex()[set.triangles[3 * j + q]];
        if (h < 0) continue;
        for (int c = 0; c < 3; ++c)
          affine_(3 * h + c, i) += l[(2 * c) * kLanes] * g[2 * q] + l[(2 * c + 1) * kLanes] * g[2 * q + 1];
      }
    }
  }
}

Eigen::VectorXd LinearStart::weights(const double* targets, double regularization) const {
  if (schur_.rows() == 0) return Eigen::VectorXd();
  const Eigen::VectorXd g =
      rest_gradient_ + affine_.transpose() * Eigen::Map<const Eigen::VectorXd>(targets, affine_.rows());
  Eigen::MatrixXd s = schur_;
  s.diagonal().array() += regularization;
  return gauss_newton_model(s, g, trust_region_scale(s)).delta;
}

}  // namespace meshik
