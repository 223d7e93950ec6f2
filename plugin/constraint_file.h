// One frame of a MeshIK constraint file for the plugin, read through the constraint-file library
// (cpp_core/constraints, the pipeline's reader too), with the solver options the file sets. The
// file's "rest" and "examples" are not used: the plugin takes the meshes from MeshLab layers.
#pragma once

#include <meshik/meshik.h>

#include <QString>

#include <optional>
#include <vector>

namespace meshik::plugin {

// The solver options a constraint file sets at its top level; each is empty when the file leaves it out.
struct FileSolverOptions {
  std::optional<FeatureSpace> feature_space;     // "feature_space"
  std::optional<Blend> blend;                    // "blend"
  std::optional<int> regions;                    // "regions" as a count, or kAutomaticRegions for "auto"
  std::optional<double> region_smoothness;       // "region_smoothness"
  std::optional<double> weight_regularization;   // "weight_regularization"
  std::optional<double> handle_stiffness;        // "handle_stiffness"
  std::optional<int> max_iterations;             // "max_iterations"
  std::optional<double> tolerance;               // "tolerance"
};

// The handles and their targets in one frame.
struct ConstraintFrame {
  QString name;                 // the frame's name ("0001" ... when the file gives none)
  int index = 0;                // the frame's 0-based position in the file
  std::vector<int> handles;     // #H vertex indices of all handle groups
  std::vector<double> targets;  // #H by 3 row-major target positions, in the order of handles
  // #V region ids of the file's "regions" vertex groups (in the file's order; -1: in no group),
  // or empty when the file gives no vertex groups.
  std::vector<int> vertex_regions;
  FileSolverOptions options;  // the file's solver options (regions given as vertex groups: above)
};

// Reads the constraint file at `path` and resolves frame `frame` against the rest mesh.
//   frame:         a frame name, or else a 0-based frame index ("0", "12")
//   rest_vertices: #V by 3 row-major rest positions (regions and rigid motions use them)
// Throws meshik::constraints::ConstraintError, whose message names the file and the JSON path
// (a region group's vertex out of range included).
ConstraintFrame readConstraintFrame(const QString& path, const QString& frame, const double* rest_vertices,
                                    int num_vertices);

}  // namespace meshik::plugin
