// Keeps the last example set and the last factored solver of the plugin, so that running the pose
// filter again with the same rest layer, example layers, handle set and options only solves
// (moving the handles changes only the right-hand side: no new factorization).
#pragma once

#include <meshik/meshik.h>

#include <memory>
#include <mutex>
#include <vector>

namespace meshik::plugin {

// What an example set is built from (copies of the layers' arrays).
struct ExampleSetInputs {
  std::vector<double> rest;                   // #V by 3 row-major rest positions
  std::vector<int> triangles;                 // #F by 3 row-major vertex indices
  std::vector<std::vector<double>> examples;  // #E arrays, each #V by 3 row-major
};

class SolverCache {
 public:
  // The example set built from `inputs`: the previous one when the inputs equal the previous
  // call's, else a new one (validated and precomputed here on `threads` threads, 0 = all cores;
  // throws meshik::InputError).
  std::shared_ptr<const ExampleSet> exampleSet(ExampleSetInputs inputs, const ProgressCallback& progress,
                                               int threads = 0);

  // A solver over `examples` for #H `handles` and `options`: the previous one when all three
  // equal the previous call's, else a new one (factored here; throws meshik::InputError).
  // Sets *reused to whether the previous solver was returned.
  std::shared_ptr<const Solver> solver(const std::shared_ptr<const ExampleSet>& examples,
                                       const std::vector<int>& handles, const SolverOptions& options,
                                       const ProgressCallback& progress, bool* reused);

 private:
  std::mutex mutex_;  // pymeshlab runs filters with the GIL released: two MeshSets may call at once
  ExampleSetInputs example_inputs_;
  std::shared_ptr<const ExampleSet> example_set_;
  std::vector<int> handles_;
  SolverOptions options_;
  std::shared_ptr<const Solver> solver_;
};

}  // namespace meshik::plugin
