// Solver: validates a handle set, factors its system once, and poses the mesh per target set.
#include "example_set_impl.h"
#include "gauss_newton.h"
#include "input_validation.h"
#include "pose_evaluation.h"
#include "pose_system.h"

namespace meshik {

struct Solver::Impl {
  std::shared_ptr<const ExampleSet> examples;
  std::vector<int> handles;
  SolverOptions options;
  std::unique_ptr<PoseSystem> system;
};

Solver::Solver(std::shared_ptr<const ExampleSet> examples, const std::vector<int>& handles,
               const SolverOptions& options, const ProgressCallback& progress)
    : impl_(std::make_unique<Impl>()) {
  if (!examples) throw InputError("no example set given to the solver");
  validate_options(options);
  const ExampleSet::Impl& set = examples->impl();
  validate_handles(handles, set.num_vertices, set.components);
  impl_->examples = std::move(examples);
  impl_->handles = handles;
  impl_->options = options;
  impl_->system = std::make_unique<PoseSystem>(set, handles, progress);
}

Solver::~Solver() = default;
Solver::Solver(Solver&&) noexcept = default;
Solver& Solver::operator=(Solver&&) noexcept = default;

SolveResult Solver::solve(const double* targets, const double* initial_weights,
                          const ProgressCallback& progress) const {
  const ExampleSet::Impl& set = impl_->examples->impl();
  validate_targets(targets, impl_->handles);
  if (initial_weights != nullptr) validate_finite(initial_weights, set.num_examples, "initial weight");
  const SolverOptions& options = impl_->options;
  Eigen::VectorXd start;
  if (initial_weights == nullptr && options.feature_space == FeatureSpace::kNonlinear &&
      set.num_examples > 0) {
    PoseEvaluator linear(set, *impl_->system, FeatureSpace::kLinear, options.weight_regularization, targets);
    start = linear_space_weights(linear, set.num_examples);
    initial_weights = start.data();
  }
  PoseEvaluator evaluator(set, *impl_->system, options.feature_space, options.weight_regularization, targets);
  return gauss_newton(evaluator, set.num_examples, set.num_triangles, initial_weights, options, progress);
}

const ExampleSet& Solver::examples() const { return *impl_->examples; }
const std::vector<int>& Solver::handles() const { return impl_->handles; }
const SolverOptions& Solver::options() const { return impl_->options; }

}  // namespace meshik
