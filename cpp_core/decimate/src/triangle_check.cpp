// Checks of a decimation request (see triangle_check.h).
#include "triangle_check.h"

#include <string>
#include <unordered_map>

namespace meshik {
namespace decimation {

namespace {

// "triangle f", as the messages name it.
std::string describe(int f) { return "triangle " + std::to_string(f); }

}  // namespace

void check_triangles(const MeshView& rest) {
  std::unordered_map<long long, int> directed_edges;
  for (int f = 0; f < rest.num_triangles; ++f) {
    const int* t = rest.triangles + 3 * static_cast<size_t>(f);
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= rest.num_vertices)
        throw InputError(describe(f) + " has vertex " + std::to_string(t[k]) + ", out of range (the mesh has " +
                         std::to_string(rest.num_vertices) + " vertices)");
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw InputError(describe(f) + " repeats a vertex (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ")");
    for (int k = 0; k < 3; ++k) {
      const long long key = static_cast<long long>(t[k]) * rest.num_vertices + t[(k + 1) % 3];
      const auto inserted = directed_edges.emplace(key, f);
      if (!inserted.second)
        throw InputError(describe(f) + " and " + describe(inserted.first->second) + " both run along the edge from vertex " +
                         std::to_string(t[k]) + " to " + std::to_string(t[(k + 1) % 3]) +
                         ": the mesh is not consistently oriented or not manifold there");
    }
  }
}

void check_vertex_fans(const MeshView& rest) {
  // Around vertex v each triangle (v, a, b) is a link edge a -> b. With every directed edge used
  // once, each link vertex starts and ends at most one link edge, so the link is a set of paths
  // and cycles; one fan means exactly one of them: walk it from its start and count.
  const int n = rest.num_vertices;
  std::vector<int> first(n + 1, 0), link;
  for (int i = 0; i < 3 * rest.num_triangles; ++i) ++first[rest.triangles[i] + 1];
  for (int v = 0; v < n; ++v) first[v + 1] += first[v];
  std::vector<int> fill(first.begin(), first.end() - 1), triangle_of(3 * static_cast<size_t>(rest.num_triangles));
  for (int f = 0; f < rest.num_triangles; ++f)
    for (int k = 0; k < 3; ++k) triangle_of[fill[rest.triangles[3 * f + k]]++] = 3 * f + k;
  std::unordered_map<int, int> next, previous;
  for (int v = 0; v < n; ++v) {
    next.clear();
    previous.clear();
    for (int i = first[v]; i < first[v + 1]; ++i) {
      const int corner = triangle_of[i], f = corner / 3, k = corner % 3;
      const int a = rest.triangles[3 * f + (k + 1) % 3], b = rest.triangles[3 * f + (k + 2) % 3];
      next[a] = b;
      previous[b] = a;
    }
    const int count = first[v + 1] - first[v];
    if (count == 0) continue;
    int start = next.begin()->first;
    for (const auto& edge : next)
      if (!previous.count(edge.first)) start = edge.first;  // a path's start (none on a cycle)
    int walked = 0;
    for (auto at = next.find(start); at != next.end() && walked < count; at = next.find(at->second)) ++walked;
    if (walked != count)
      throw InputError("vertex " + std::to_string(v) + " joins " + std::to_string(count) +
                       " triangles that form more than one fan (e.g. " + describe(triangle_of[first[v]] / 3) +
                       "): the mesh is not manifold there");
  }
}

void check_request(int num_vertices, const std::vector<int>& locked, int target_triangles, const DistanceBound& bound) {
  if (target_triangles < 1) throw InputError("the target triangle count must be at least 1");
  if (!(bound.max_distance > 0.0)) throw InputError("the distance bound must be positive (infinity for none)");
  if (!(bound.relax_factor > 1.0) || bound.max_relaxations < 0)
    throw InputError("the distance bound's relax factor must exceed 1 and its relaxation count be at least 0");
  for (int v : locked) {
    if (v < 0 || v >= num_vertices)
      throw InputError("locked vertex " + std::to_string(v) + " is out of range (the mesh has " +
                       std::to_string(num_vertices) + " vertices)");
  }
}

}  // namespace decimation
}  // namespace meshik
