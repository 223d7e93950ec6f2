// Wall-clock times of the phases of a computation, kept for benchmarks (never printed by the core).
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace meshik {

// (phase name, milliseconds) in the order the phases ran.
using PhaseTimes = std::vector<std::pair<std::string, double>>;

// Records laps: lap(name) adds the time since the previous lap (or construction) under name.
class PhaseClock {
 public:
  explicit PhaseClock(PhaseTimes& times) : times_(times), last_(std::chrono::steady_clock::now()) {}

  void lap(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    times_.emplace_back(name, std::chrono::duration<double, std::milli>(now - last_).count());
    last_ = now;
  }

 private:
  PhaseTimes& times_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace meshik
