// Reads one frame of a MeshIK constraint file (format "meshik-constraints", version 1, the
// pipeline's format; see pipeline/README.md) for the plugin. Only QtCore: no MeshLab types.
//
// The subset the plugin needs: the handle groups (vertex index lists, or {"near": [x, y, z],
// "radius": r} regions of the rest mesh) and the targets of one frame (per-vertex [[x, y, z], ...]
// lists, or rigid motions {"translate"}, {"rotate": {"axis", "degrees", "center"}}, {"matrix"} of
// the group's rest positions). A group missing from a frame keeps its previous targets, its rest
// positions before the first frame that names it. The file's "rest", "examples" and solver
// options are not used: the plugin takes the meshes from MeshLab layers and the options from its
// parameters.
#pragma once

#include <QString>

#include <stdexcept>
#include <vector>

namespace meshik::plugin {

// A bad constraint file. The message names the file and the JSON path:
// "shot.json: frames[3].targets.head: expected 3 numbers, got a list of 2".
class ConstraintFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The handles and their targets in one frame.
struct ConstraintFrame {
  QString name;                 // the frame's name ("0001" ... when the file gives none)
  int index = 0;                // the frame's 0-based position in the file
  std::vector<int> handles;     // #H vertex indices of all handle groups
  std::vector<double> targets;  // #H by 3 row-major target positions, in the order of handles
};

// Reads the constraint file at `path` and resolves frame `frame` against the rest mesh.
//   frame:         a frame name, or else a 0-based frame index ("0", "12")
//   rest_vertices: #V by 3 row-major rest positions (regions and rigid motions use them)
// Throws ConstraintFileError.
ConstraintFrame readConstraintFrame(const QString& path, const QString& frame, const double* rest_vertices,
                                    int num_vertices);

}  // namespace meshik::plugin
