// One frame of a MeshIK constraint file for the plugin, read through the constraint-file library
// (cpp_core/constraints, the pipeline's reader too). The file's "rest", "examples" and solver
// options are not used, but for regions given as vertex groups (no parameter can give those): the
// plugin takes the meshes from MeshLab layers and the other options from its parameters.
#pragma once

#include <QString>

#include <vector>

namespace meshik::plugin {

// The handles and their targets in one frame.
struct ConstraintFrame {
  QString name;                 // the frame's name ("0001" ... when the file gives none)
  int index = 0;                // the frame's 0-based position in the file
  std::vector<int> handles;     // #H vertex indices of all handle groups
  std::vector<double> targets;  // #H by 3 row-major target positions, in the order of handles
  // #V region ids of the file's "regions" vertex groups (in the file's order; -1: in no group),
  // or empty when the file gives no vertex groups.
  std::vector<int> vertex_regions;
};

// Reads the constraint file at `path` and resolves frame `frame` against the rest mesh.
//   frame:         a frame name, or else a 0-based frame index ("0", "12")
//   rest_vertices: #V by 3 row-major rest positions (regions and rigid motions use them)
// Throws meshik::constraints::ConstraintError, whose message names the file and the JSON path
// (a region group's vertex out of range included).
ConstraintFrame readConstraintFrame(const QString& path, const QString& frame, const double* rest_vertices,
                                    int num_vertices);

}  // namespace meshik::plugin
