// Writes the tool's handles and their current targets as a one-frame MeshIK constraint file
// (format "meshik-constraints", version 1: see pipeline/README.md) through the constraint-file
// library (cpp_core/constraints), so that a drag session replays in the batch pipeline
// (`meshik.constraints.load`). Plain C++: no Qt, no MeshLab.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace meshik::edit {

// Everything the file holds.
struct DragFrame {
  std::string rest_path;                   // the rest mesh's file (absolute)
  std::vector<std::string> example_paths;  // #E example files (absolute)
  bool linear_feature_space = false;       // "feature_space": "linear" (else "nonlinear")
  double weight_regularization = 0.0;
  int max_iterations = 30;
  std::string group_name = "drag";         // the one handle group's name
  std::string frame_name = "drag";         // the one frame's name (letters, digits, "._-")
  std::vector<int> handles;                // #H vertex indices
  std::vector<double> targets;             // #H by 3 row-major targets, in the order of handles
};

// A frame that cannot be written; the message names the file and the element.
class ConstraintWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `frame` to `path`: into a temporary file beside it, then renamed over `path`, so the
// file is either the old one or the complete new one. Throws ConstraintWriteError when a target
// is not finite, a handle repeats or is negative, there is no handle, a path is empty, or the
// file cannot be written.
void writeConstraintFrame(const std::string& path, const DragFrame& frame);

}  // namespace meshik::edit
