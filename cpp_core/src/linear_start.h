// The weights that minimise the energy in the linear feature space, for any targets of one handle
// set, without a solve per pose.
//
// In the linear space F_j(w) = U_j + sum_i w_i L_ij, so the Gauss-Newton matrix
// S = L^T L - H^T K'^{-1} H (H = G'^T L) does not depend on w or on the targets, and neither
// does Z = K'^{-1} H. The Gauss-Newton right-hand side at w = 0 is affine in the targets x_h:
//   g = H^T x0 - L^T s,  x0 = K'^{-1} (G'^T U - K_fh x_h),  s = U - (handles' part of Q)
//     = g_U - Z^T K_fh x_h + L^T (handles' part of Q)  =  g_U + A^T x_h,
// with g_U the value for x_h = 0. One evaluation per handle set gives S, g_U and Z; A (#H 3 by #E)
// only needs Z's rows next to the handles. The optimal weights are then (S + kappa I)^+ g.
// They start the nonlinear space's iterations (the rest pose may lie in the basin of a worse local
// minimum) and are the linear space's solution.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "example_set_impl.h"
#include "pose_evaluation.h"
#include "pose_system.h"

namespace meshik {

// The linear space's Gauss-Newton system at w = 0 with every handle at the origin, assembled but
// not solved: the part of a LinearStart that reads the handle set's rows, coupling and partition
// but not its factor, so it may be built while the system is factored.
struct LinearStartAssembly {
  std::vector<double> origin;                // #H by 3 zeros: the evaluator's targets
  std::unique_ptr<PoseEvaluator> evaluator;  // assembled at zero weights; null without examples
};

// set / system: the example set and its handle system (rows numbered; factored or not); buffers:
// the evaluation's storage, sized (and its pages touched) here; team: threads of the assembly (a
// thread_count; the same bits for any team). Returns the assembly LinearStart finishes.
LinearStartAssembly assemble_linear_start(const ExampleSet::Impl& set, const PoseSystem& system,
                                          EvaluationBuffers& buffers, int team = 1);

class LinearStart {
 public:
  // set / system: the example set and its factored handle system. One Gauss-Newton system (the
  // forward solve of 3 (#E + 1) right-hand sides) and the backward solve on the handles' tree
  // paths. team: threads of those passes (a thread_count; the same bits for any team). buffers:
  // the evaluation's storage, left sized (and its pages touched) for the poses that reuse it.
  LinearStart(const ExampleSet::Impl& set, const PoseSystem& system, EvaluationBuffers& buffers, int team = 1)
      : LinearStart(set, system, assemble_linear_start(set, system, buffers, team), team) {}
  // The same from assemble_linear_start's result for this set and system (its buffers are left
  // sized for the poses), solved once the system is factored.
  LinearStart(const ExampleSet::Impl& set, const PoseSystem& system, LinearStartAssembly assembly, int team = 1);

  // targets: #H by 3 handle positions; regularization: kappa >= 0. Returns #E weights.
  Eigen::VectorXd weights(const double* targets, double regularization) const;

 private:
  Eigen::MatrixXd schur_;          // #E by #E: S without kappa
  Eigen::VectorXd rest_gradient_;  // #E: g_U
  Eigen::MatrixXd affine_;         // #H 3 by #E: A
};

}  // namespace meshik
