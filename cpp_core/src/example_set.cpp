// ExampleSet: validation and precomputation of the rest mesh and the examples, and blend().
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <numeric>

#include "analysis_cache.h"
#include "example_set_impl.h"
#include "gradient_operator.h"
#include "heap_release.h"
#include "input_validation.h"
#include "locality_order.h"
#include "meshik/thread_limit.h"
#include "page_arrays.h"
#include "page_pool.h"
#include "phase_clock.h"
#include "pose_evaluation.h"
#include "pose_system.h"
#include "thread_count.h"

namespace meshik {

ExampleSet::Impl::Impl() = default;
ExampleSet::Impl::~Impl() = default;

std::vector<double> ExampleSet::Impl::to_internal(const double* positions) const {
  std::vector<double> internal(3 * static_cast<size_t>(num_vertices));
  to_internal(positions, internal.data());
  return internal;
}

void ExampleSet::Impl::to_internal(const double* positions, double* internal) const {
  for (int v = 0; v < num_vertices; ++v)
    std::copy(positions + 3 * static_cast<size_t>(vertex_of_internal[v]),
              positions + 3 * static_cast<size_t>(vertex_of_internal[v]) + 3, internal + 3 * static_cast<size_t>(v));
}

std::vector<double> ExampleSet::Impl::to_user(const std::vector<double>& positions) const {
  std::vector<double> user(positions.size());
  for (int v = 0; v < num_vertices; ++v)
    std::copy(positions.begin() + 3 * static_cast<size_t>(v), positions.begin() + 3 * static_cast<size_t>(v) + 3,
              user.begin() + 3 * static_cast<size_t>(vertex_of_internal[v]));
  return user;
}

namespace {

// Fills the per-component rest centroids and example centroid shifts of impl.
void compute_centroids(ExampleSet::Impl& impl, const std::vector<const double*>& examples) {
  const int count = impl.components.count;
  const int k = impl.num_examples;
  impl.rest_centroid.assign(3 * static_cast<size_t>(count), 0.0);
  impl.centroid_shift.assign(3 * static_cast<size_t>(count) * k, 0.0);
  std::vector<int> size(count, 0);
  for (int v = 0; v < impl.num_vertices; ++v) {
    const int c = impl.components.component_of_vertex[v];
    if (c < 0) continue;
    ++size[c];
    for (int d = 0; d < 3; ++d) {
      const double rest = impl.rest[3 * static_cast<size_t>(v) + d];
      impl.rest_centroid[3 * c + d] += rest;
      for (int i = 0; i < k; ++i)
        impl.centroid_shift[3 * (static_cast<size_t>(c) * k + i) + d] +=
            examples[i][3 * static_cast<size_t>(v) + d] - rest;
    }
  }
  for (int c = 0; c < count; ++c)
    for (int d = 0; d < 3; ++d) {
      impl.rest_centroid[3 * c + d] /= size[c];
      for (int i = 0; i < k; ++i) impl.centroid_shift[3 * (static_cast<size_t>(c) * k + i) + d] /= size[c];
    }
}

// One vertex of every connected component (the first in index order).
std::vector<int> component_anchors(const VertexComponents& components) {
  std::vector<int> anchors(components.count, -1);
  for (size_t v = 0; v < components.component_of_vertex.size(); ++v) {
    const int c = components.component_of_vertex[v];
    if (c >= 0 && anchors[c] < 0) anchors[c] = static_cast<int>(v);
  }
  return anchors;
}

}  // namespace

ExampleSet::ExampleSet(const MeshView& rest, const std::vector<const double*>& examples,
                       const ProgressCallback& progress, int threads, FeaturePrecision precision)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  PhaseClock clock(impl.phase_times);
  validate_rest_mesh(rest);
  validate_examples(examples, rest.num_vertices);
  clock.lap("validation");
  if (progress && !progress(0.0, "validated input")) throw Cancelled("cancelled after validation");
  impl.num_vertices = rest.num_vertices;
  impl.num_triangles = rest.num_triangles;
  impl.num_examples = static_cast<int>(examples.size());
  if (threads < 0 || threads > kMaxThreads)
    throw InputError("threads must be 0 (all cores) or a count from 1 to " + std::to_string(kMaxThreads) + ", got " +
                     std::to_string(threads));
  const int team = thread_count(threads);
  LocalityOrder order = locality_order(rest.triangles, rest.num_triangles, rest.num_vertices);
  impl.vertex_of_internal = std::move(order.vertex_of_internal);
  impl.internal_of_vertex = std::move(order.internal_of_vertex);
  impl.triangles.reserve(3 * static_cast<size_t>(rest.num_triangles));
  for (int j : order.triangle_order)
    for (int q = 0; q < 3; ++q) impl.triangles.push_back(impl.internal_of_vertex[rest.triangles[3 * j + q]]);
  impl.triangle_of_internal = std::move(order.triangle_order);
  impl.components = std::move(order.components);
  clock.lap("locality order");
  const int* triangles = impl.triangles.data();
  // The analysis of an earlier ExampleSet of these triangles (analysis_cache.h), or the system's
  // rows (the vertices of the components, in the internal order), its pattern and an analysis of
  // it (ordering and symbolic factorization: serial, about 0.6 s at 1M triangles). These need the
  // triangles only: with more than one thread they run on a thread of their own, started as soon
  // as the triangles are in the internal order, beside the copies of the positions, the frames and
  // the features, the rows and pattern announced by `rows_ready` (waited for before the
  // centroids), the analysis after them. They write system_row_of_vertex, built_pattern and
  // system_analysis alone; the analysis is waited for below (or, should anything throw first, by
  // the future's destructor, before what it uses goes).
  const bool cached = share_cached_analysis(impl.triangles, rest.num_vertices, impl.system_analysis);
  CscMatrix built_pattern;
  const auto number_rows = [&impl, &built_pattern, &rest, triangles, cached] {
    impl.system_row_of_vertex.assign(rest.num_vertices, -1);
    int system_rows = 0;
    for (int v = 0; v < rest.num_vertices; ++v)
      if (impl.components.component_of_vertex[v] >= 0) impl.system_row_of_vertex[v] = system_rows++;
    if (!cached)
      built_pattern = eliminated_lower_pattern(triangles, rest.num_triangles, impl.system_row_of_vertex, system_rows);
  };
  const CscMatrix& pattern = cached ? impl.system_analysis.analyzed_pattern() : built_pattern;
  const auto analyze = [&impl, &pattern] {
    if (pattern.rows > 0) impl.system_analysis.analyze(pattern);
  };
  std::promise<void> rows_ready;
  std::future<void> rows = rows_ready.get_future();
  std::future<void> analysis;
  if (!cached && team > 1) {
    analysis = std::async(std::launch::async, [&number_rows, &analyze, &rows_ready] {
      try {
        number_rows();
      } catch (...) {
        rows_ready.set_exception(std::current_exception());
        return;
      }
      rows_ready.set_value();
      analyze();
    });
  } else {
    number_rows();
    rows_ready.set_value();
  }
  // The team less the core the analysis thread holds while it runs, for the frames, the adjacency,
  // the features and the normal matrix (each the same for any team): the analysis is the longest
  // task here, and sharing its core with the team's passes only delays it.
  const auto team_beside_analysis = [&analysis, team] {
    const bool running =
        analysis.valid() && analysis.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
    return running ? std::max(1, team - 1) : team;
  };
  impl.rest = impl.to_internal(rest.vertices);
  // The examples in the internal order, copied on the whole team beside the starting analysis
  // thread (one example per thread at a time; an allocation failure is rethrown after the loop),
  // first touched by the copy.
  const int num_examples = impl.num_examples;
  std::vector<PageArray<double>> internal_examples(num_examples);
  std::vector<std::exception_ptr> copy_failure(num_examples);
#pragma omp parallel for schedule(static, 1) num_threads(team) if (team > 1 && num_examples > 1)
  for (int i = 0; i < num_examples; ++i) {
    try {
      size_unwritten(internal_examples[i], 3 * static_cast<size_t>(rest.num_vertices));
      impl.to_internal(examples[i], internal_examples[i].data());
    } catch (...) {
      copy_failure[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& failure : copy_failure)
    if (failure) std::rethrow_exception(failure);
  std::vector<const double*> example_pointers;
  for (const PageArray<double>& e : internal_examples) example_pointers.push_back(e.data());
  clock.lap("copies");
  impl.frames = compute_triangle_frames(impl.rest.data(), triangles, rest.num_triangles, team_beside_analysis());
  TriangleAdjacency adjacency =
      triangle_adjacency(triangles, rest.num_triangles, rest.num_vertices, team_beside_analysis());
  clock.lap("topology and frames");
  impl.features =
      compute_example_features(impl.frames, adjacency, triangles, example_pointers, progress, true, threads, precision,
                               team_beside_analysis);
  // The features took the frames' plane bases: only the in-plane gradients are read after this,
  // and the adjacency nowhere.
  adjacency = TriangleAdjacency();
  clock.lap("features");
  rows.get();  // the system's rows and pattern
  compute_centroids(impl, example_pointers);
  // Nor the examples (their copies in the internal order).
  example_pointers.clear();
  internal_examples = std::vector<PageArray<double>>();
  clock.lap("centroids");
  // Only the values are kept here: the analysis holds the pattern.
  impl.system_values =
      eliminated_lower_values(impl.frames, triangles, impl.system_row_of_vertex, pattern, team_beside_analysis());
  clock.lap("normal matrix");
  if (analysis.valid())
    analysis.get();
  else if (!cached)
    analyze();
  if (!cached) cache_analysis(impl.triangles, rest.num_vertices, impl.system_analysis);
  // The temporaries above (the examples' copies, the adjacency, the frames' released parts, the
  // analysis thread's work arrays) leave holes in the heaps: many are given back before the
  // Solver, a few kept for its allocations (heap_release.h).
  release_free_heap_memory();
  clock.lap(cached ? "analysis (cached)" : "analysis");  // with more than one thread: the wait for it
}

// The set's arrays, and the pages the pool kept for its Solvers, go back to the system.
ExampleSet::~ExampleSet() {
  if (!impl_) return;
  impl_.reset();
  release_pooled_pages();
}
ExampleSet::ExampleSet(ExampleSet&&) noexcept = default;
ExampleSet& ExampleSet::operator=(ExampleSet&&) noexcept = default;

int ExampleSet::num_vertices() const { return impl_->num_vertices; }
int ExampleSet::num_triangles() const { return impl_->num_triangles; }
int ExampleSet::num_examples() const { return impl_->num_examples; }
FeaturePrecision ExampleSet::feature_precision() const { return impl_->features.precision; }

std::vector<double> ExampleSet::blend(const double* weights, FeatureSpace feature_space, Blend blend) const {
  const Impl& impl = *impl_;
  const int k = impl.num_examples;
  if (k > 0 && weights == nullptr) throw InputError("no weights given to blend");
  validate_finite(weights, k, "weight");
  std::call_once(impl.blend_system_once, [&impl] {
    impl.blend_system = std::make_unique<PoseSystem>(impl, component_anchors(impl.components));
  });
  // Anchors at the origin fix each component's translation; shift it afterwards.
  const std::vector<double> origin(3 * impl.blend_system->handles().size(), 0.0);
  EvaluationBuffers buffers;
  PoseEvaluator evaluator(impl, *impl.blend_system, feature_space, 0.0, origin.data(), buffers, 1, blend);
  PoseEvaluation pose;
  evaluator.evaluate(weights, false, pose);

  const int count = impl.components.count;
  std::vector<double> shift(3 * static_cast<size_t>(count), 0.0);
  std::vector<int> size(count, 0);
  for (int v = 0; v < impl.num_vertices; ++v) {
    const int c = impl.components.component_of_vertex[v];
    if (c < 0) continue;
    ++size[c];
    for (int d = 0; d < 3; ++d) shift[3 * c + d] -= pose.vertices[3 * static_cast<size_t>(v) + d];
  }
  for (int c = 0; c < count; ++c)
    for (int d = 0; d < 3; ++d) {
      double target = impl.rest_centroid[3 * c + d];
      for (int i = 0; i < k; ++i)
        target += weights[i] * impl.centroid_shift[3 * (static_cast<size_t>(c) * k + i) + d];
      shift[3 * c + d] = shift[3 * c + d] / size[c] + target;
    }
  for (int v = 0; v < impl.num_vertices; ++v) {
    const int c = impl.components.component_of_vertex[v];
    if (c < 0) continue;
    for (int d = 0; d < 3; ++d) pose.vertices[3 * static_cast<size_t>(v) + d] += shift[3 * c + d];
  }
  for (double x : pose.vertices)
    if (!std::isfinite(x))
      throw InputError("the blend leaves the finite range of double precision: the weights are too large for this mesh");
  return impl.to_user(pose.vertices);
}

}  // namespace meshik
