// Orders for cache locality: the solver's passes go over triangles and touch their corners'
// rows, so vertices that share triangles should be close in memory and consecutive triangles
// should share vertices. Meshes as stored often are not (the elephant's triangles span about
// 9,000 vertex indices on average).
#pragma once

#include <vector>

#include "mesh_topology.h"

namespace meshik {

struct LocalityOrder {
  std::vector<int> vertex_of_internal;  // #V: the user's index of each internal vertex
  std::vector<int> internal_of_vertex;  // #V: the internal index of each user vertex
  std::vector<int> triangle_order;      // #F: the user's index of each internal triangle
  // The connected components of the internal vertices (linked by sharing a triangle), numbered by
  // their least internal vertex: the runs of the breadth-first order.
  VertexComponents components;
};

// triangles: #F by 3 vertex indices in [0, num_vertices). Vertices in breadth-first
// (Cuthill-McKee) order over the triangles' edges from a lowest-degree vertex of each connected
// component, vertices used by no triangle last; triangles by their smallest internal vertex.
LocalityOrder locality_order(const int* triangles, int num_triangles, int num_vertices);

}  // namespace meshik
