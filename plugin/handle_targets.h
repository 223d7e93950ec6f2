// Where the pose filter's handles and their targets come from: the rest layer's selection moved
// to a target layer's positions or by a 4x4 transform, or a frame of a constraint file.
#pragma once

#include "constraint_file.h"

#include <common/ml_document/mesh_document.h>
#include <common/parameters/rich_parameter_list.h>

#include <QString>

#include <vector>

namespace meshik::plugin {

// The values of the "targetsource" parameter.
enum class TargetSource { kTargetLayer = 0, kConstraintFile = 1, kHandleTransform = 2 };

// Adds "targetsource", "targetmesh", "constraintfile", "frame" and "handletransform".
void addHandleTargetParameters(RichParameterList& parameters, const MeshDocument& document);

// The target layer when "targetsource" is a target layer (compacted), else null. Throws
// MLException when the layer does not exist or has another vertex count than `rest`.
MeshModel* targetLayer(const RichParameterList& parameters, MeshDocument& document, const MeshModel& rest);

struct HandleTargets {
  std::vector<int> handles;     // #H ascending vertex indices
  std::vector<double> targets;  // #H by 3 row-major targets, in the order of handles
  QString source;               // where the targets came from, for the log
  // A constraint file's vertex-group regions (ConstraintFrame::vertex_regions), else empty.
  std::vector<int> vertex_regions;
  // A constraint file's solver options (ConstraintFrame::options), else all empty.
  FileSolverOptions file_options;
};

// The handles and targets for the rest layer (#V by 3 row-major `rest_positions`):
//   target layer:     the selected vertices, at their positions in `target` (from targetLayer());
//   handle transform: the selected vertices, moved by the 4x4 matrix;
//   constraint file:  the file's handles in the chosen frame; when vertices are selected, only
//                     those (each must be one of the file's handles); its vertex-group regions and
//                     its solver options.
// Throws MLException when no vertex is selected (layer / transform) or on a bad constraint file.
HandleTargets handleTargets(const RichParameterList& parameters, const MeshModel& rest,
                            const std::vector<double>& rest_positions, const MeshModel* target);

}  // namespace meshik::plugin
