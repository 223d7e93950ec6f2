// The normals of a posed triangle mesh on flat arrays: unit face normals, and unit vertex normals
// weighted by the area of the triangles around each vertex (MeshLab's "Re-Compute Vertex
// Normals" with area weighting). The solve worker computes them beside each pose, so that the GUI
// thread only copies them into the layer.
#pragma once

#include <vector>

namespace meshik::edit {

struct SurfaceNormals {
  std::vector<double> faces;     // #F by 3 unit normals, (p1 - p0) x (p2 - p0) normalized; 0 when degenerate
  std::vector<double> vertices;  // #V by 3 unit normals; 0 for a vertex of no (or only degenerate) triangles
};

// positions: #V by 3 row-major; triangles: #F by 3 0-based vertex indices (each below #V).
// Returns the face and vertex normals.
SurfaceNormals surfaceNormals(const std::vector<double>& positions, const std::vector<int>& triangles);

}  // namespace meshik::edit
