// The safeguarded Gauss-Newton loop over the blend weights: trust-region steps of the quadratic
// model with the Gauss-Newton matrix S plus the energy's second-order term.
#include "gauss_newton.h"

#include <string>
#include <utility>

#include "trust_region.h"

namespace meshik {

namespace {

// Energy per triangle below which a decrease is rounding noise (the energy is dimensionless:
// squared differences of deformation gradients, O(1) per triangle).
constexpr double kNoiseEnergyPerTriangle = 1e-20;

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
  double radius = -1.0;  // set from the first Gauss-Newton step
  while (k > 0) {
    const Eigen::VectorXd scale = trust_region_scale(current.schur);
    const GaussNewtonModel gauss_newton = gauss_newton_model(current.schur, current.step_rhs, scale);
    if (!(gauss_newton.decrease > options.tolerance * current.energy + noise)) {
      result.converged = true;
      break;
    }
    if (result.iterations == options.max_iterations) break;
    if (radius < 0.0) radius = gauss_newton.scaled_length;
    if (!current.has_second_order) evaluator.add_second_order(current);
    const TrustRegionStep step = trust_region_step(current.schur + current.second_order,
                                                   current.step_rhs, scale, radius);
    if (!(step.scaled_length > 0.0)) break;  // the trust region has collapsed
    const Eigen::VectorXd next = Eigen::Map<const Eigen::VectorXd>(current.weights.data(), k) + step.delta;
    evaluator.evaluate(next.data(), true, trial);
    ++result.iterations;
    if (progress && !progress(static_cast<double>(result.iterations) / options.max_iterations,
                              "Gauss-Newton iteration " + std::to_string(result.iterations)))
      throw Cancelled("cancelled at Gauss-Newton iteration " + std::to_string(result.iterations));

    const double decrease = current.energy - trial.energy;
    radius = updated_radius(radius, step, decrease);
    if (decrease >= 0.0) {
      const double before = current.energy;
      std::swap(current, trial);
      result.energies.push_back(current.energy);
      if (decrease <= options.tolerance * before + noise && !step.on_boundary) {
        result.converged = true;
        break;
      }
    }
  }
  result.vertices = std::move(current.vertices);
  result.weights = std::move(current.weights);
  result.residual = current.energy;
  result.inverted_triangles = std::move(current.inverted_triangles);
  return result;
}

}  // namespace meshik
