#include "solver_cache.h"

namespace meshik::plugin {
namespace {

bool sameInputs(const ExampleSetInputs& a, const ExampleSetInputs& b) {
  return a.rest == b.rest && a.triangles == b.triangles && a.examples == b.examples;
}

bool sameOptions(const SolverOptions& a, const SolverOptions& b) {
  return a.feature_space == b.feature_space && a.weight_regularization == b.weight_regularization &&
         a.max_iterations == b.max_iterations && a.tolerance == b.tolerance && a.threads == b.threads &&
         a.blend == b.blend && a.regions == b.regions && a.vertex_regions == b.vertex_regions &&
         a.region_smoothness == b.region_smoothness && a.handle_stiffness == b.handle_stiffness;
}

}  // namespace

std::shared_ptr<const ExampleSet> SolverCache::exampleSet(ExampleSetInputs inputs,
                                                          const ProgressCallback& progress, int threads) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (example_set_ && sameInputs(inputs, example_inputs_)) return example_set_;
  MeshView rest;
  rest.vertices = inputs.rest.data();
  rest.num_vertices = static_cast<int>(inputs.rest.size() / 3);
  rest.triangles = inputs.triangles.data();
  rest.num_triangles = static_cast<int>(inputs.triangles.size() / 3);
  std::vector<const double*> examples;
  for (const std::vector<double>& example : inputs.examples) examples.push_back(example.data());
  auto example_set = std::make_shared<const ExampleSet>(rest, examples, progress, threads);
  example_inputs_ = std::move(inputs);
  example_set_ = example_set;
  solver_.reset();
  return example_set;
}

std::shared_ptr<const Solver> SolverCache::solver(const std::shared_ptr<const ExampleSet>& examples,
                                                  const std::vector<int>& handles,
                                                  const SolverOptions& options,
                                                  const ProgressCallback& progress, bool* reused) {
  std::lock_guard<std::mutex> lock(mutex_);
  *reused = solver_ && examples == example_set_ && handles == handles_ && sameOptions(options, options_);
  if (*reused) return solver_;
  auto solver = std::make_shared<const Solver>(examples, handles, options, progress);
  if (examples == example_set_) {
    handles_ = handles;
    options_ = options;
    solver_ = solver;
  }
  return solver;
}

}  // namespace meshik::plugin
