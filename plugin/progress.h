// MeshLab's progress callback (vcg::CallBackPos: percent and message) seen as the MeshIK core's
// ProgressCallback over one stretch of the filter's run.
#pragma once

#include <meshik/meshik.h>
#include <wrap/callback.h>

namespace meshik::plugin {

// A core progress callback that reports its fraction f in [0, 1] to MeshLab as
// begin + f * (end - begin) percent with the stage name. `callback` may be null (no reporting).
// Returns false (the core then cancels) when MeshLab's callback does.
ProgressCallback progressRange(vcg::CallBackPos* callback, int begin, int end);

}  // namespace meshik::plugin
