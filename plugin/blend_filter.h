// "MeshIK: Blend Examples" (compute_coord_meshik_blend): the combination of the example layers
// with given weights, in the nonlinear (or linear) feature space, no handles.
#pragma once

#include "filter_common.h"

#include <wrap/callback.h>

#include <QVariant>

#include <map>
#include <string>

namespace meshik::plugin {

// The filter's parameters; the default weights are 1 for the first candidate example layer of
// the document and 0 for the others.
RichParameterList blendParameters(const MeshDocument& document);

// Runs the filter: writes the blend to a new layer "MeshIK blend of <rest>". Returns
// {"layer_id": int}. Throws MLException on bad input.
std::map<std::string, QVariant> applyBlend(const RichParameterList& parameters, MeshDocument& document,
                                           vcg::CallBackPos* callback, SolverCache& cache, const Logger& log);

}  // namespace meshik::plugin
