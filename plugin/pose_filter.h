// "MeshIK: Pose from Examples" (compute_coord_meshik_pose): the current layer is the rest mesh,
// the example layers span the space of poses, the selected vertices are the handles; their
// targets come from a target layer, a constraint file frame or a 4x4 transform.
#pragma once

#include "filter_common.h"

#include <wrap/callback.h>

#include <QVariant>

#include <map>
#include <string>

namespace meshik::plugin {

// The filter's parameters, with defaults taken from the document (the current layer).
RichParameterList poseParameters(const MeshDocument& document);

// Runs the filter. Returns the values pymeshlab hands to Python:
//   "weights" (Eigen::VectorXd, #E), "iterations" (int), "residual" (double),
//   "converged" (bool), "factorization_reused" (bool), "layer_id" (int, the pose's layer),
//   "inverted_triangles" (int: faces the pose turns over against their blended deformation).
// Throws MLException (or the core's exceptions) on bad input.
std::map<std::string, QVariant> applyPose(const RichParameterList& parameters, MeshDocument& document,
                                          vcg::CallBackPos* callback, SolverCache& cache, const Logger& log);

}  // namespace meshik::plugin
