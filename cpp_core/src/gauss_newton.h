// Gauss-Newton on the blend weights with the vertices eliminated, safeguarded by
// Levenberg-Marquardt damping so that every accepted iteration lowers the energy.
#pragma once

#include "meshik/meshik.h"
#include "pose_evaluation.h"

namespace meshik {

// evaluator: set up for the handles' targets; num_examples: #E; num_triangles: #F (sets the
// energy's rounding-noise level); initial_weights: #E values or nullptr for w = 0. Each iteration solves the k x k system (S + lambda diag S) delta = g and
// evaluates w + delta (one multi-right-hand-side solve); a step that raises the energy is rejected
// and lambda raised. The damping vanishes at a stationary point (g = 0), so it does not move the
// converged solution. Stops when the predicted or the achieved relative decrease falls to
// options.tolerance (or to rounding noise) or after options.max_iterations evaluations.
SolveResult gauss_newton(PoseEvaluator& evaluator, int num_examples, int num_triangles,
                         const double* initial_weights, const SolverOptions& options,
                         const ProgressCallback& progress);

}  // namespace meshik
