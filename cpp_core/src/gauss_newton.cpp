// The damped Gauss-Newton loop over the blend weights.
#include "gauss_newton.h"

#include <algorithm>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

namespace meshik {

namespace {

constexpr double kFirstDamping = 1e-4;
constexpr double kDampingGrowth = 10.0;
constexpr double kSmallestDamping = 1e-10;
// Energy per triangle below which a decrease is rounding noise (the energy is dimensionless:
// squared differences of deformation gradients, O(1) per triangle).
constexpr double kNoiseEnergyPerTriangle = 1e-20;

// Solves (S + damping diag(S)) delta = g; returns false if the system is numerically singular.
bool damped_step(const PoseEvaluation& at, double damping, Eigen::VectorXd& delta) {
  Eigen::MatrixXd a = at.schur;
  const double scale = std::max(a.diagonal().maxCoeff(), 1e-300);
  for (int i = 0; i < a.rows(); ++i)
    a(i, i) += damping * std::max(a(i, i), 1e-12 * scale);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  if (ldlt.info() != Eigen::Success) return false;
  delta = ldlt.solve(at.step_rhs);
  return delta.allFinite();
}

}  // namespace

SolveResult gauss_newton(PoseEvaluator& evaluator, int num_examples, int num_triangles,
                         const double* initial_weights, const SolverOptions& options,
                         const ProgressCallback& progress) {
  const int k = num_examples;
  const double noise = kNoiseEnergyPerTriangle * num_triangles;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(k);
  if (initial_weights != nullptr) w = Eigen::Map<const Eigen::VectorXd>(initial_weights, k);
  PoseEvaluation current, trial;
  evaluator.evaluate(w.data(), k > 0, current);

  SolveResult result;
  result.energies.push_back(current.energy);
  double damping = 0.0;
  Eigen::VectorXd delta;
  while (k > 0) {
    const bool solvable = damped_step(current, damping, delta);
    // Decrease of the Gauss-Newton model: 2 g.delta - delta^T S delta.
    const double predicted =
        solvable ? 2.0 * current.step_rhs.dot(delta) - delta.dot(current.schur * delta) : 0.0;
    if (solvable && !(predicted > options.tolerance * current.energy + noise)) {
      result.converged = true;
      break;
    }
    if (result.iterations == options.max_iterations) break;
    if (solvable) {
      const Eigen::VectorXd next = Eigen::Map<const Eigen::VectorXd>(current.weights.data(), k) + delta;
      evaluator.evaluate(next.data(), true, trial);
    }
    ++result.iterations;
    if (progress && !progress(static_cast<double>(result.iterations) / options.max_iterations,
                              "Gauss-Newton iteration " + std::to_string(result.iterations)))
      throw Cancelled("cancelled at Gauss-Newton iteration " + std::to_string(result.iterations));
    if (solvable && trial.energy <= current.energy) {
      const double decrease = current.energy - trial.energy;
      const double before = current.energy;
      std::swap(current, trial);
      result.energies.push_back(current.energy);
      damping = damping * 0.1 < kSmallestDamping ? 0.0 : damping * 0.1;
      if (decrease <= options.tolerance * before) {
        result.converged = true;
        break;
      }
    } else {
      damping = damping == 0.0 ? kFirstDamping : damping * kDampingGrowth;
    }
  }
  result.vertices = std::move(current.vertices);
  result.weights = std::move(current.weights);
  result.residual = current.energy;
  return result;
}

}  // namespace meshik
