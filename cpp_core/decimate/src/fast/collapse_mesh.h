// The connectivity of a mesh under half-edge collapses: triangles keep their ids (a collapse
// renames a corner or deletes the triangle), every vertex lists the live triangles around it
// (the vertex -> triangle references of fast quadric simplification).
#pragma once

#include <array>
#include <vector>

namespace meshik {
namespace decimation {

class CollapseMesh {
 public:
  // triangles: #F by 3 row-major vertex ids (checked by check_corners; where the mesh is not an
  // oriented manifold the decimator locks the vertices: irregular_vertices).
  CollapseMesh(const int* triangles, int num_triangles, int num_vertices);

  // The corners of triangle t (current vertex ids, the original orientation).
  const std::array<int, 3>& corners(int t) const { return triangles_[t]; }
  bool triangle_alive(int t) const { return triangle_alive_[t] != 0; }
  // The live triangles with corner v (none once v is collapsed away).
  const std::vector<int>& triangles_around(int v) const { return around_[v]; }
  bool vertex_alive(int v) const { return vertex_alive_[v] != 0; }
  int num_triangles() const { return static_cast<int>(triangles_.size()); }
  int num_vertices() const { return static_cast<int>(around_.size()); }
  int remaining_triangles() const { return remaining_; }

  // The vertices sharing a live triangle with v, increasing.
  std::vector<int> neighbours(int v) const;
  // Whether some edge at v belongs to a single triangle (v lies on an open border).
  bool on_border(int v) const;
  // Whether collapsing v0 onto its neighbour v1 keeps the mesh manifold: the edge has one or two
  // triangles, their opposite corners are exactly the common neighbours of v0 and v1 (the link
  // condition), a border vertex moves only along its border edge, neither v0 nor an opposite
  // corner loses all its triangles, and no triangle would repeat another's corners.
  bool collapse_keeps_manifold(int v0, int v1) const;
  // Moves v0 onto v1: the triangles with both are deleted, v0 is renamed v1 in the others.
  void collapse(int v0, int v1);

 private:
  std::vector<std::array<int, 3>> triangles_;
  std::vector<char> triangle_alive_;
  std::vector<std::vector<int>> around_;
  std::vector<char> vertex_alive_;
  int remaining_;
};

}  // namespace decimation
}  // namespace meshik
