#include "solve_worker.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <utility>

namespace meshik::edit {
namespace {

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

SolveWorker::SolveWorker(std::shared_ptr<const ExampleSet> examples, SolverOptions options,
                         std::function<void()> notify, std::vector<int> triangles)
    : examples_(std::move(examples)),
      options_(options),
      notify_(std::move(notify)),
      triangles_(std::move(triangles)),
      thread_([this] { run(); }) {}

SolveWorker::~SolveWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    pending_.reset();
  }
  wake_.notify_all();
  idle_.notify_all();
  thread_.join();
}

void SolveWorker::post(SolveRequest request) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    counts_.moves += request.moves;
    if (pending_) {
      ++counts_.coalesced;
      request.moves += pending_->moves;
      request.first_event = std::min(request.first_event, pending_->first_event);
      if (!request.start_weights) request.start_weights = std::move(pending_->start_weights);
      request.quick = request.quick && pending_->quick;  // a full request stays full
    }
    pending_ = std::move(request);
  }
  wake_.notify_one();
}

std::optional<SolveOutcome> SolveWorker::take() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<SolveOutcome> outcome = std::move(finished_);
  finished_.reset();
  return outcome;
}

void SolveWorker::poseWritten() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    awaiting_write_ = false;
  }
  wake_.notify_one();
}

void SolveWorker::waitIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  awaiting_write_ = false;
  wake_.notify_one();
  idle_.wait(lock, [this] { return (!pending_ && !running_) || stop_; });
}

SolveWorker::Counts SolveWorker::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

void SolveWorker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return (pending_.has_value() && !awaiting_write_) || stop_; });
    if (stop_) return;
    SolveRequest request = std::move(*pending_);
    pending_.reset();
    running_ = true;
    lock.unlock();
    SolveOutcome outcome = solve(request);
    lock.lock();
    running_ = false;
    outcome.number = static_cast<std::uint64_t>(++counts_.solves);
    if (finished_) ++counts_.superseded;
    finished_ = std::move(outcome);
    awaiting_write_ = true;
    if (!pending_) idle_.notify_all();
    if (notify_) {
      lock.unlock();
      notify_();
      lock.lock();
    }
  }
}

SolveOutcome SolveWorker::solve(const SolveRequest& request) {
  SolveOutcome outcome;
  outcome.request = request;
  try {
    if (request.start_weights) warm_weights_ = *request.start_weights;
    const Solver& solver = solverFor(request, outcome);
    const Clock::time_point start = Clock::now();
    // Weights of another length (kept from before the blend's regions changed) are no warm start.
    const bool warm = warm_weights_.size() == static_cast<size_t>(solver.num_weights());
    outcome.result = solver.solve(request.targets.data(), warm ? warm_weights_.data() : nullptr);
    outcome.solve_ms = millisecondsSince(start);
    for (size_t i = 0; i < outcome.result.vertices.size(); ++i)
      if (!std::isfinite(outcome.result.vertices[i]))
        throw std::runtime_error("the solve gave vertex " + std::to_string(i / 3) + " a non-finite position");
    warm_weights_ = outcome.result.weights;
    if (!triangles_.empty()) {
      const Clock::time_point normals_start = Clock::now();
      outcome.normals = surfaceNormals(outcome.result.vertices, triangles_);
      outcome.normals_ms = millisecondsSince(normals_start);
    }
  } catch (const std::exception& error) {
    outcome.error = error.what();
    outcome.result = SolveResult{};
    outcome.normals = SurfaceNormals{};
  }
  outcome.finished = Clock::now();
  return outcome;
}

const Solver& SolveWorker::solverFor(const SolveRequest& request, SolveOutcome& outcome) {
  std::shared_ptr<const Solver>& solver = request.quick ? quick_solver_ : full_solver_;
  if (!solver || solver->handles() != request.handles) {
    const Clock::time_point start = Clock::now();
    solver.reset();  // free the old factorization first
    SolverOptions options = options_;
    if (request.quick) options.max_iterations = 1;
    solver = std::make_shared<const Solver>(examples_, request.handles, options);
    outcome.refactored = true;
    outcome.factor_ms = millisecondsSince(start);
  }
  return *solver;
}

}  // namespace meshik::edit
