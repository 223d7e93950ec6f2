// Solver: validates a handle set, factors its system once, and poses the mesh per target set.
#include <algorithm>
#include <functional>
#include <mutex>

#include "blend_regions.h"
#include "example_set_impl.h"
#include "gauss_newton.h"
#include "input_validation.h"
#include "linear_start.h"
#include "pose_evaluation.h"
#include "pose_system.h"
#include "rest_example.h"
#include "thread_count.h"

namespace meshik {

using BuffersPool = std::vector<std::unique_ptr<EvaluationBuffers>>;

struct Solver::Impl {
  std::shared_ptr<const ExampleSet> examples;
  std::vector<int> handles;
  SolverOptions options;
  std::unique_ptr<PoseSystem> system;
  std::unique_ptr<LinearStart> linear_start;
  // Spatially varying weights (SolverOptions::regions, vertex_regions), or null for one vector.
  std::unique_ptr<BlendRegions> regions;
  // The free blend's examples: the rest pose, then the set's (rest_example.h); null for affine.
  std::unique_ptr<ExampleFeatures> free_features;
  // The examples a weight vector blends: #E, or #E + 1 with the free blend (the rest pose first).
  int blended_examples() const { return free_features ? free_features->num_examples : examples->num_examples(); }
  // Evaluation buffers of finished solves, reused by the next ones (one per concurrent solve).
  std::mutex pool_mutex;
  BuffersPool pool;
};

namespace {

// Takes buffers from a pool (or new ones) and gives them back when destroyed.
class BuffersLease {
 public:
  BuffersLease(std::mutex& mutex, BuffersPool& pool) : mutex_(mutex), pool_(pool) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pool_.empty()) {
      buffers_ = std::make_unique<EvaluationBuffers>();
    } else {
      buffers_ = std::move(pool_.back());
      pool_.pop_back();
    }
  }
  ~BuffersLease() {
    std::lock_guard<std::mutex> lock(mutex_);
    pool_.push_back(std::move(buffers_));
  }
  BuffersLease(const BuffersLease&) = delete;
  BuffersLease& operator=(const BuffersLease&) = delete;
  EvaluationBuffers& buffers() { return *buffers_; }

 private:
  std::mutex& mutex_;
  BuffersPool& pool_;
  std::unique_ptr<EvaluationBuffers> buffers_;
};

}  // namespace

Solver::Solver(std::shared_ptr<const ExampleSet> examples, const std::vector<int>& handles,
               const SolverOptions& options, const ProgressCallback& progress)
    : impl_(std::make_unique<Impl>()) {
  if (!examples) throw InputError("no example set given to the solver");
  validate_options(options);
  const ExampleSet::Impl& set = examples->impl();
  validate_handles(handles, set.num_vertices, set.components, set.internal_of_vertex);
  std::vector<int> internal_handles;
  for (int v : handles) internal_handles.push_back(set.internal_of_vertex[v]);
  impl_->examples = std::move(examples);
  impl_->handles = handles;
  impl_->options = options;
  const int team = thread_count(options.threads);
  // The linear start's buffers are the first poses' (the pool's first entry): sized and touched.
  // Its assembly needs no factor: with more than one thread, one more thread assembles it while
  // the team factors the system (the same bits as after it). Its buffers then sit beside the
  // factorization's work arrays instead of replacing them: at 1.08M triangles (121 MB of buffers)
  // on 2 threads the peak is about 50 MB higher (941 against 890 MB) and the Solver about 0.19 s
  // faster (bench/README.md).
  auto buffers = std::make_unique<EvaluationBuffers>();
  LinearStartAssembly assembly;
  std::function<void(const PoseSystem&)> assemble_beside;
  if (team > 1)
    assemble_beside = [&](const PoseSystem& system) { assembly = assemble_linear_start(set, system, *buffers, 1); };
  impl_->system =
      std::make_unique<PoseSystem>(set, internal_handles, progress, team, options.handle_stiffness, assemble_beside);
  if (!assemble_beside) assembly = assemble_linear_start(set, *impl_->system, *buffers, team);
  impl_->linear_start = std::make_unique<LinearStart>(set, *impl_->system, std::move(assembly), team);
  impl_->pool.push_back(std::move(buffers));
  if (options.blend == Blend::kFree) impl_->free_features = std::make_unique<ExampleFeatures>(with_rest_example(set.features));
  if (!options.vertex_regions.empty())
    impl_->regions = std::make_unique<BlendRegions>(
        regions_from_vertex_groups(set, options.vertex_regions, options.region_smoothness));
  else if (options.regions != 1)
    impl_->regions = std::make_unique<BlendRegions>(regions_from_examples(*impl_->examples, options.regions, options.region_smoothness));
}

Solver::~Solver() = default;
Solver::Solver(Solver&&) noexcept = default;
Solver& Solver::operator=(Solver&&) noexcept = default;

SolveResult Solver::solve(const double* targets, const double* initial_weights,
                          const ProgressCallback& progress) const {
  const ExampleSet::Impl& set = impl_->examples->impl();
  validate_targets(targets, impl_->handles);
  if (initial_weights != nullptr) validate_finite(initial_weights, num_weights(), "initial weight");
  const SolverOptions& options = impl_->options;
  BuffersLease lease(impl_->pool_mutex, impl_->pool);
  const int team = thread_count(options.threads);
  const ExampleFeatures* features = impl_->free_features.get();  // null: the set's
  const int blended = impl_->blended_examples();
  Eigen::VectorXd start;
  if (initial_weights == nullptr) {
    start = impl_->linear_start->weights(targets, options.weight_regularization);
    if (features != nullptr) {  // the rest pose's weight 1 - sum w_i: the affine blend's stretch
      Eigen::VectorXd with_rest(blended);
      with_rest << 1.0 - start.sum(), start;
      start = with_rest;
    }
    if (impl_->regions) {
      // Regions start from the one global vector that solves the pose without them (from the
      // linear space's), every region alike: the regions' solve then only lowers that energy.
      PoseEvaluator global(set, *impl_->system, options.feature_space, options.weight_regularization, targets,
                           lease.buffers(), team, options.blend, nullptr, features);
      const SolveResult one = gauss_newton(global, blended, set.num_triangles, start.data(), options, {});
      start = Eigen::Map<const Eigen::VectorXd>(one.weights.data(), blended).replicate(num_regions(), 1);
    }
    initial_weights = start.data();
  }
  PoseEvaluator evaluator(set, *impl_->system, options.feature_space, options.weight_regularization, targets,
                          lease.buffers(), team, options.blend, impl_->regions.get(), features);
  SolveResult result =
      gauss_newton(evaluator, evaluator.num_weights(), set.num_triangles, initial_weights, options, progress);
  result.vertices = set.to_user(result.vertices);
  validate_pose_finite(result, targets, impl_->handles);
  for (int& j : result.inverted_triangles) j = set.triangle_of_internal[j];
  std::sort(result.inverted_triangles.begin(), result.inverted_triangles.end());
  return result;
}

const ExampleSet& Solver::examples() const { return *impl_->examples; }
const std::vector<int>& Solver::handles() const { return impl_->handles; }
const SolverOptions& Solver::options() const { return impl_->options; }
int Solver::num_regions() const { return impl_->regions ? impl_->regions->num_regions : 1; }
int Solver::num_weights() const { return num_regions() * impl_->blended_examples(); }

std::vector<int> Solver::triangle_regions() const {
  const ExampleSet::Impl& set = impl_->examples->impl();
  std::vector<int> region(set.num_triangles, 0);
  if (!impl_->regions) return region;
  const int count = impl_->regions->num_regions;
  for (int j = 0; j < set.num_triangles; ++j) {
    const double* share = impl_->regions->share.data() + static_cast<size_t>(j) * count;
    region[set.triangle_of_internal[j]] = static_cast<int>(std::max_element(share, share + count) - share);
  }
  return region;
}

}  // namespace meshik
