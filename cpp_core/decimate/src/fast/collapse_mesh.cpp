// Connectivity under half-edge collapses (see collapse_mesh.h).
#include "collapse_mesh.h"

#include <algorithm>
#include <iterator>

namespace meshik {
namespace decimation {

namespace {

// Takes a triangle's corners and one of them; returns the corner's position in it (0, 1 or 2).
int corner_index(const std::array<int, 3>& t, int v) { return t[0] == v ? 0 : (t[1] == v ? 1 : 2); }

bool has_corner(const std::array<int, 3>& t, int v) { return t[0] == v || t[1] == v || t[2] == v; }

}  // namespace

CollapseMesh::CollapseMesh(const int* triangles, int num_triangles, int num_vertices)
    : triangles_(num_triangles),
      triangle_alive_(num_triangles, 1),
      around_(num_vertices),
      vertex_alive_(num_vertices, 1),
      remaining_(num_triangles) {
  for (int t = 0; t < num_triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      triangles_[t][k] = triangles[3 * static_cast<size_t>(t) + k];
      around_[triangles_[t][k]].push_back(t);
    }
  }
}

std::vector<int> CollapseMesh::neighbours(int v) const {
  std::vector<int> result;
  for (int t : around_[v])
    for (int c : triangles_[t])
      if (c != v) result.push_back(c);
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

bool CollapseMesh::on_border(int v) const {
  // each triangle (v, a, b) has the edges v->a and b->v: an inner edge v-x has both directions
  std::vector<int> out, in;
  for (int t : around_[v]) {
    const int k = corner_index(triangles_[t], v);
    out.push_back(triangles_[t][(k + 1) % 3]);
    in.push_back(triangles_[t][(k + 2) % 3]);
  }
  std::sort(out.begin(), out.end());
  std::sort(in.begin(), in.end());
  return out != in;
}

bool CollapseMesh::collapse_keeps_manifold(int v0, int v1) const {
  std::vector<int> opposite;
  for (int t : around_[v0]) {
    if (!has_corner(triangles_[t], v1)) continue;
    for (int c : triangles_[t])
      if (c != v0 && c != v1) opposite.push_back(c);
  }
  const size_t shared = opposite.size();
  if (shared == 0 || shared > 2 || around_[v0].size() <= shared) return false;
  if (on_border(v0) && shared != 1) return false;  // a border vertex moves along its border only
  for (int o : opposite)
    if (around_[o].size() <= 1) return false;
  std::sort(opposite.begin(), opposite.end());
  const std::vector<int> n0 = neighbours(v0), n1 = neighbours(v1);
  std::vector<int> common;
  std::set_intersection(n0.begin(), n0.end(), n1.begin(), n1.end(), std::back_inserter(common));
  if (common != opposite) return false;
  // no triangle renamed onto v1 may repeat one of v1's (a tetrahedron would fold into two)
  for (int t : around_[v0]) {
    const std::array<int, 3>& moved = triangles_[t];
    if (has_corner(moved, v1)) continue;
    for (int u : around_[v1]) {
      const std::array<int, 3>& kept = triangles_[u];
      int same = 0;
      for (int c : moved) same += c != v0 && has_corner(kept, c);
      if (same == 2) return false;
    }
  }
  return true;
}

void CollapseMesh::collapse(int v0, int v1) {
  for (int t : around_[v0]) {
    std::array<int, 3>& corners = triangles_[t];
    if (has_corner(corners, v1)) {
      triangle_alive_[t] = 0;
      --remaining_;
      for (int c : corners) {
        if (c == v0) continue;
        std::vector<int>& list = around_[c];
        list.erase(std::find(list.begin(), list.end(), t));
      }
    } else {
      corners[corner_index(corners, v0)] = v1;
      around_[v1].push_back(t);
    }
  }
  around_[v0].clear();
  vertex_alive_[v0] = 0;
}

}  // namespace decimation
}  // namespace meshik
