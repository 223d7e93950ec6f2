// Connectivity of a triangle mesh: connected components of the vertices used by triangles (as
// locality_order finds them), and the edge adjacency and components of triangles.
#pragma once

#include <vector>

namespace meshik {

// Vertex components of the graph whose edges are the triangles' edges.
struct VertexComponents {
  // #V: component id in [0, count) of each vertex, or -1 for a vertex used by no triangle.
  std::vector<int> component_of_vertex;
  int count = 0;
};

// Triangles sharing an edge, in compressed rows: the neighbours of triangle j are
// neighbour[start[j] .. start[j+1]). A non-manifold edge makes all its triangles neighbours.
struct TriangleAdjacency {
  std::vector<int> start;      // #F + 1
  std::vector<int> neighbour;  // sum of the neighbour counts
};

// triangles: #F by 3 row-major vertex indices (valid, in [0, num_vertices)); team: the threads to
// use (the same adjacency for any team).
TriangleAdjacency triangle_adjacency(const int* triangles, int num_triangles, int num_vertices, int team = 1);

// Connected components of the triangles through their adjacency.
struct TriangleComponents {
  std::vector<int> component_of;  // #F: component id in [0, count), numbered by least triangle
  int count = 0;
};

TriangleComponents triangle_components(const TriangleAdjacency& adjacency);

}  // namespace meshik
