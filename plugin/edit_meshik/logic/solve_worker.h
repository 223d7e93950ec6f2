// Solves poses on a thread of its own while the GUI thread goes on handling the mouse.
//
// The GUI thread posts one request per mouse move. A request posted while another waits replaces
// it (coalescing: only the newest targets matter), so a slow solve never builds a queue; the
// worker always ends on the newest targets. A new handle set refactors (a new Solver); a move
// only solves, warm-started from the previous pose's weights. A quick request (a move during a
// drag) takes one Gauss-Newton step from there, which the warm start makes nearly the whole way
// (the full solve's second step typically only confirms convergence); a full request (the end of
// a drag) iterates to convergence. Quick and full requests use two solvers (each factors once per
// handle set), since the iteration limit is a solver option. Finished poses are handed back
// through take() on the GUI thread, which alone writes the mesh; `notify` (called on the
// worker's thread) tells it there is one. Given the triangles, the worker also computes each
// pose's normals, so that the GUI thread only copies them. The worker starts no solve while a
// finished pose waits to be written (from its hand-over to poseWritten()): the GUI thread's write
// into the layer and MeshLab's GL buffers then has the cores to itself instead of sharing them with
// the next solve (on 2 cores, that sharing made the elephant's write 3-8x slower).
#pragma once

#include "surface_normals.h"

#include <meshik/meshik.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace meshik::edit {

using Clock = std::chrono::steady_clock;

struct SolveRequest {
  std::vector<int> handles;     // #H vertex indices
  std::vector<double> targets;  // #H by 3 row-major targets, in the order of handles
  // Set: start from these #E weights instead of the previous pose's (empty: from the rest pose,
  // after "Reset pose"; the weights of an undone pose after undo or redo).
  std::optional<std::vector<double>> start_weights;
  bool quick = false;           // one Gauss-Newton step (during a drag) instead of convergence
  int moves = 1;                // mouse moves folded into this request
  Clock::time_point first_event = Clock::now();  // when the oldest of them happened
};

struct SolveOutcome {
  SolveRequest request;       // what was solved (moves and first_event include coalesced ones)
  SolveResult result;         // the pose (empty vertices when `error` is set)
  SurfaceNormals normals;     // the pose's normals (empty without triangles or with `error`)
  std::string error;          // why the solve failed (a handle set the core refuses, ...)
  bool refactored = false;    // a new handle set: the solver was factored for this request
  double factor_ms = 0.0;     // time spent factoring (0 when not refactored)
  double solve_ms = 0.0;      // time spent in Solver::solve
  double normals_ms = 0.0;    // time spent computing the normals
  Clock::time_point finished;  // when the worker finished it
  std::uint64_t number = 0;   // 1 for the worker's first solve, 2 for the next, ...
};

class SolveWorker {
 public:
  // examples: the example set every pose is solved in; options: the solver options;
  // notify: called on the worker's thread after each finished request (may be empty);
  // triangles: #F by 3 vertex indices of the rest mesh, for the normals (empty: none computed).
  SolveWorker(std::shared_ptr<const ExampleSet> examples, SolverOptions options, std::function<void()> notify,
              std::vector<int> triangles = {});
  // Waits for the running solve, drops a waiting request, stops the thread.
  ~SolveWorker();
  SolveWorker(const SolveWorker&) = delete;
  SolveWorker& operator=(const SolveWorker&) = delete;

  // Queues `request`, replacing (and folding in) a request that waits and has not started.
  void post(SolveRequest request);

  // The newest finished outcome not taken yet, or none. An outcome that finished while an older
  // one still waited replaces it (counted in Counts::superseded: the GUI was busy drawing).
  std::optional<SolveOutcome> take();

  // Called by the GUI thread once it has written the outcome it took: the worker may start the
  // next solve.
  void poseWritten();

  // Blocks until no request waits or runs (for tests and for saving a finished pose); lets the
  // worker go on without poseWritten() (the caller is not writing while it waits).
  void waitIdle();

  // Mouse moves posted, requests solved, requests replaced by a newer one before they started,
  // finished outcomes replaced by a newer one before they were taken.
  struct Counts {
    int moves = 0;
    int solves = 0;
    int coalesced = 0;
    int superseded = 0;
  };
  Counts counts() const;

 private:
  void run();
  SolveOutcome solve(const SolveRequest& request);
  // The solver for the request's handle set and kind (quick or full), factored when it is new.
  const Solver& solverFor(const SolveRequest& request, SolveOutcome& outcome);

  const std::shared_ptr<const ExampleSet> examples_;
  const SolverOptions options_;
  const std::function<void()> notify_;
  const std::vector<int> triangles_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::optional<SolveRequest> pending_;
  std::optional<SolveOutcome> finished_;
  bool running_ = false;
  bool awaiting_write_ = false;  // a finished outcome was handed over and is not written yet
  bool stop_ = false;
  Counts counts_;

  // Touched only by the worker thread.
  std::shared_ptr<const Solver> full_solver_;
  std::shared_ptr<const Solver> quick_solver_;
  std::vector<double> warm_weights_;

  std::thread thread_;  // last: starts after everything above is ready
};

}  // namespace meshik::edit
