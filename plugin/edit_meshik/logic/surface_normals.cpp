#include "surface_normals.h"

#include <cmath>
#include <cstddef>

namespace meshik::edit {
namespace {

// Scales the 3-vector at `v` to unit length (leaves a zero vector zero).
void normalize(double* v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (length > 0.0)
    for (int k = 0; k < 3; ++k) v[k] /= length;
}

}  // namespace

SurfaceNormals surfaceNormals(const std::vector<double>& positions, const std::vector<int>& triangles) {
  SurfaceNormals normals;
  normals.faces.assign(triangles.size(), 0.0);
  normals.vertices.assign(positions.size(), 0.0);
  for (std::size_t f = 0; f < triangles.size() / 3; ++f) {
    const double* p0 = &positions[3 * static_cast<std::size_t>(triangles[3 * f])];
    const double* p1 = &positions[3 * static_cast<std::size_t>(triangles[3 * f + 1])];
    const double* p2 = &positions[3 * static_cast<std::size_t>(triangles[3 * f + 2])];
    const double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    const double b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    double* n = &normals.faces[3 * f];
    n[0] = a[1] * b[2] - a[2] * b[1];  // twice the area times the unit normal: the area weighting
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) normals.vertices[3 * static_cast<std::size_t>(triangles[3 * f + corner]) + k] += n[k];
    normalize(n);
  }
  for (std::size_t v = 0; v < positions.size() / 3; ++v) normalize(&normals.vertices[3 * v]);
  return normals;
}

}  // namespace meshik::edit
