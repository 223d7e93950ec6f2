// Drag latencies (mouse-move event to updated GL buffers) collected over one drag.
#pragma once

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

// The timings of the poses applied during one drag or turn, in milliseconds: latency (mouse-move
// event to updated GL buffers) = waiting for the worker (a solve in flight) + solve + overhead,
// overhead = waiting for the GUI thread (worker done to the pose taken up on the GUI thread) +
// writing (the layer's positions and normals, then MeshLab's GL buffers).
struct DragTimings {
  LatencyStats latency, solve, overhead, waiting, writing;
  void clear() {
    for (LatencyStats* stats : {&latency, &solve, &overhead, &waiting, &writing}) stats->clear();
  }
};

}  // namespace meshik::edit
