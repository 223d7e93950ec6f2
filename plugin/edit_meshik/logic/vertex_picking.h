// Which vertex or handle a click means, given the projection the mesh was drawn with.
#pragma once

#include "screen_projection.h"

#include <vector>

namespace meshik::edit {

// The vertex a click at window point (x, y) means, where the depth buffer there reads
// `surface_depth` (1 or more: nothing drawn there). Among the #V vertices (#V by 3 row-major
// `vertices`) drawn within `radius` pixels of the click, the one nearest in space to the surface
// point under the click, so that a vertex on the far side of the mesh is never taken.
// Returns its index, or -1 when nothing is drawn there or no vertex is that close.
int pickVertex(const ScreenProjection& projection, const std::vector<double>& vertices, double x, double y,
               double surface_depth, double radius);

// The handle whose marker is under the click at (x, y): among the #H points (#H by 3 row-major
// `points`, the handles' current targets) drawn within `radius` pixels, the nearest to the click
// (the front one of equally near ones). Returns its position in `points`, or -1.
int pickHandle(const ScreenProjection& projection, const std::vector<double>& points, double x, double y,
               double radius);

}  // namespace meshik::edit
