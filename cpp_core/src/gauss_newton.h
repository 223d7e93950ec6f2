// Gauss-Newton on the blend weights with the vertices eliminated (DESIGN.md section 2), safeguarded
// by a trust region so that every accepted iteration lowers the energy.
//
// Each iteration evaluates the pose at the trial weights with one multi-right-hand-side solve
// (pose_evaluation.h) and forms the k x k model of the reduced energy phi(w) = min_x E(x, w):
// the Gauss-Newton matrix S plus the energy's second-order term -sum_j <R_j, d2F_j/dw2> (exact
// Hessian; zero in the linear space). Far from the minimum that model may be indefinite, so the
// step minimises it within a trust region |D delta| <= radius (D = sqrt diag S) whose radius grows
// while the model predicts the energy well and shrinks when it does not; steps that raise the
// energy are rejected. At a minimum the gradient vanishes and the step is the unconstrained model
// step, so the safeguard does not move the converged solution; near it convergence is quadratic
// where plain Gauss-Newton's is only linear for poses away from the examples.
#pragma once

#include "meshik/meshik.h"
#include "pose_evaluation.h"

namespace meshik {

// evaluator: set up for the handles' targets; num_examples: its weights' count K (#E, or #regions
// by #E); num_triangles: #F (sets the energy's rounding-noise level); initial_weights: K values or
// nullptr for w = 0.
// Stops (converged) when the Gauss-Newton model predicts, or an interior step achieves, a relative
// decrease of at most options.tolerance (or only rounding noise); or after options.max_iterations
// evaluations. The result's vertices and inverted_triangles are in the evaluator's internal order.
SolveResult gauss_newton(PoseEvaluator& evaluator, int num_examples, int num_triangles,
                         const double* initial_weights, const SolverOptions& options,
                         const ProgressCallback& progress);

}  // namespace meshik
