// Which vertex or handle a click means, given the projection the mesh was drawn with.
#pragma once

#include "screen_projection.h"

#include <functional>
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

// The vertices (of #V by 3 row-major `vertices`) drawn inside the window rectangle with corners
// (x0, y0) and (x1, y1) that lie on the visible surface: within `tolerance` (a distance in mesh
// units) of the surface point the depth buffer shows at their pixel. `surface_depth(px, py)` reads
// the depth buffer at window pixel (px, py) (1 or more: nothing drawn). Ascending indices.
std::vector<int> pickVerticesInRectangle(const ScreenProjection& projection, const std::vector<double>& vertices,
                                         double x0, double y0, double x1, double y1,
                                         const std::function<double(int, int)>& surface_depth, double tolerance);

}  // namespace meshik::edit
