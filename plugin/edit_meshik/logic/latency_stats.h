// Drag latencies (mouse-move event to updated GL buffers) collected over one drag.
#pragma once

#include <chrono>
#include <initializer_list>
#include <vector>

namespace meshik::edit {

class LatencyStats {
 public:
  void add(double milliseconds) { samples_.push_back(milliseconds); }
  void clear() { samples_.clear(); }
  int count() const { return static_cast<int>(samples_.size()); }
  // The median (mean of the two middle samples for an even count); 0 when empty.
  double median() const;
  // The largest sample; 0 when empty.
  double max() const;

 private:
  std::vector<double> samples_;
};

// The GUI thread's parts of writing one pose, in milliseconds: when it began (the end of waiting
// for the GUI thread), copying positions and normals into the layer, waiting for the view's
// renderer to finish what it was drawing (glFinish on the view's context), MeshLab's GL buffers
// (meshAttributesUpdated + manageBuffers; replicated: the view draws face normals, so MeshLab
// uploads 3 vertices per triangle), the selection overlay.
struct PoseWriteTimes {
  std::chrono::steady_clock::time_point start;
  double copy_ms = 0.0, backlog_ms = 0.0, buffers_ms = 0.0, selection_ms = 0.0;
  double writing_ms = 0.0;  // the whole write, its parts and bookkeeping, less the renderer backlog
  bool replicated = false;
};

// The timings of the poses applied during one drag or turn, in milliseconds: latency (mouse-move
// event to updated GL buffers) = waiting for the worker (a solve in flight) + solve + overhead,
// overhead = waiting for the GUI thread (worker done to the pose taken up on the GUI thread) +
// writing (the layer's positions and normals, then MeshLab's GL buffers, of which `buffers` is
// MeshLab's part) + the renderer backlog (see PoseWriteTimes).
struct DragTimings {
  LatencyStats latency, solve, overhead, waiting, writing, buffers, backlog;
  void clear() {
    for (LatencyStats* stats : {&latency, &solve, &overhead, &waiting, &writing, &buffers, &backlog}) stats->clear();
  }
};

}  // namespace meshik::edit
