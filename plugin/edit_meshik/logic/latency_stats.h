// Drag latencies (mouse-move event to updated GL buffers) collected over one drag.
#pragma once

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

}  // namespace meshik::edit
