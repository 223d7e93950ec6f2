// The OpenMesh mesh type of the decimator and the vertex positions of every pose it decimates for.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cstddef>
#include <vector>

namespace meshik {
namespace decimation {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
using Vec = OpenMesh::Vec3d;

// Vertex positions of every pose (rest first): #P pointers to #V by 3 row-major arrays.
struct Poses {
  std::vector<const double*> positions;
  int num_vertices = 0;

  // Position of original vertex `vertex` in pose `pose`.
  Vec at(int pose, int vertex) const {
    const double* p = positions[pose] + 3 * static_cast<size_t>(vertex);
    return Vec(p[0], p[1], p[2]);
  }
  int count() const { return static_cast<int>(positions.size()); }
};

}  // namespace decimation
}  // namespace meshik
