// Writes the tool's handle groups and its keyframes (each group's targets per frame) as a MeshIK
// constraint file (format "meshik-constraints", version 1: see pipeline/README.md) through the
// constraint-file library (cpp_core/constraints), so that an animation posed by dragging in
// MeshLab replays in the batch pipeline (`meshik pose`, `meshik batch`). A group of two or more
// vertices whose targets are a rigid motion of its rest positions is written as that motion
// ("rotate" about its rest centroid, then "translate"); others as position lists. Plain C++: no
// Qt, no MeshLab.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace meshik::edit {

// One handle group: its name and its rest-mesh vertices, in the order of its targets.
struct DragGroup {
  std::string name;
  std::vector<int> vertices;
};

// One frame: its name (letters, digits, "._-") and per group (in the order of the file's groups)
// its #vertices by 3 row-major targets; empty targets leave the group out of the frame (it keeps
// its previous targets).
struct DragKeyframe {
  std::string name;
  std::vector<std::vector<double>> targets;
};

// Everything the file holds.
struct DragFrames {
  std::string rest_path;                   // the rest mesh's file (absolute)
  std::vector<std::string> example_paths;  // #E example files (absolute)
  bool linear_feature_space = false;       // "feature_space": "linear" (else "nonlinear")
  double weight_regularization = 0.0;
  bool free_blend = false;                 // "blend": "free" (else "affine")
  int regions = 1;                         // "regions": a count >= 1, or meshik::kAutomaticRegions ("auto")
  double region_smoothness = 0.01;         // "region_smoothness", written with more than one region
  double handle_stiffness = 0.0;           // "handle_stiffness", written when > 0 (soft handles)
  int max_iterations = 30;
  std::vector<DragGroup> groups;
  std::vector<DragKeyframe> frames;
};

// A file that cannot be written; the message names the file and the element.
class ConstraintWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `frames` to `path`: into a temporary file beside it, then renamed over `path`, so the
// file is either the old one or the complete new one. rest_vertices: the rest mesh's #V by 3
// row-major positions (num_vertices = #V) for the rigid fit and the range check; null: every
// target is written as positions and the vertices are checked when the file is read.
// Throws ConstraintWriteError when a target is not finite, a vertex repeats or is out of range,
// there is no group or frame, a path is empty, or the file cannot be written.
void writeConstraintFrames(const std::string& path, const DragFrames& frames, const double* rest_vertices,
                           int num_vertices);

}  // namespace meshik::edit
