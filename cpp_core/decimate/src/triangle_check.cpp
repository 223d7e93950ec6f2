// Checks of a decimation request (see triangle_check.h).
#include "triangle_check.h"

#include <string>
#include <unordered_map>

namespace meshik {
namespace decimation {

namespace {

// "triangle f", as the messages name it.
std::string describe(int f) { return "triangle " + std::to_string(f); }

// Two triangles running along one directed edge from `from` to `to`: `later` after `earlier`.
struct SharedEdge {
  int later, earlier, from, to;
};

// Takes the rest mesh (after check_corners); calls visit(SharedEdge) for every triangle that runs
// along a directed edge an earlier triangle already ran along, in triangle order, until visit
// returns false.
template <class Visit>
void for_each_shared_edge(const MeshView& rest, Visit visit) {
  std::unordered_map<long long, int> directed_edges;
  for (int f = 0; f < rest.num_triangles; ++f) {
    const int* t = rest.triangles + 3 * static_cast<size_t>(f);
    for (int k = 0; k < 3; ++k) {
      const long long key = static_cast<long long>(t[k]) * rest.num_vertices + t[(k + 1) % 3];
      const auto inserted = directed_edges.emplace(key, f);
      if (!inserted.second && !visit(SharedEdge{f, inserted.first->second, t[k], t[(k + 1) % 3]})) return;
    }
  }
}

// The triangles around every vertex of a mesh, to walk each vertex's fans.
class VertexFans {
 public:
  explicit VertexFans(const MeshView& rest) : rest_(rest), first_(rest.num_vertices + 1, 0) {
    for (int i = 0; i < 3 * rest.num_triangles; ++i) ++first_[rest.triangles[i] + 1];
    for (int v = 0; v < rest.num_vertices; ++v) first_[v + 1] += first_[v];
    std::vector<int> fill(first_.begin(), first_.end() - 1);
    corner_.resize(3 * static_cast<size_t>(rest.num_triangles));
    for (int f = 0; f < rest.num_triangles; ++f)
      for (int k = 0; k < 3; ++k) corner_[fill[rest.triangles[3 * f + k]]++] = 3 * f + k;
  }

  // How many triangles have corner v.
  int count(int v) const { return first_[v + 1] - first_[v]; }

  // Whether v's triangles form one fan (joined edge to edge), given that no directed edge from or
  // to v is used twice. Around v each triangle (v, a, b) is a link edge a -> b; each link vertex
  // then starts and ends at most one link edge, so the link is a set of paths and cycles, and one
  // fan means exactly one of them: walk it from its start and count.
  bool one_fan(int v) {
    next_.clear();
    previous_.clear();
    for (int i = first_[v]; i < first_[v + 1]; ++i) {
      const int f = corner_[i] / 3, k = corner_[i] % 3;
      const int a = rest_.triangles[3 * f + (k + 1) % 3], b = rest_.triangles[3 * f + (k + 2) % 3];
      next_[a] = b;
      previous_[b] = a;
    }
    if (count(v) == 0) return true;
    int start = next_.begin()->first;
    for (const auto& edge : next_)
      if (!previous_.count(edge.first)) start = edge.first;  // a path's start (none on a cycle)
    int walked = 0;
    for (auto at = next_.find(start); at != next_.end() && walked < count(v); at = next_.find(at->second)) ++walked;
    return walked == count(v);
  }

 private:
  const MeshView& rest_;
  std::vector<int> first_, corner_;
  std::unordered_map<int, int> next_, previous_;
};

}  // namespace

void check_corners(const MeshView& rest) {
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
  }
}

void check_triangles(const MeshView& rest) {
  check_corners(rest);
  for_each_shared_edge(rest, [](const SharedEdge& e) -> bool {
    throw InputError(describe(e.later) + " and " + describe(e.earlier) + " both run along the edge from vertex " +
                     std::to_string(e.from) + " to " + std::to_string(e.to) +
                     ": the mesh is not consistently oriented or not manifold there");
  });
}

std::vector<char> irregular_vertices(const MeshView& rest) {
  std::vector<char> irregular(rest.num_vertices, 0);
  for_each_shared_edge(rest, [&](const SharedEdge& e) {
    irregular[e.from] = irregular[e.to] = 1;
    return true;
  });
  VertexFans fans(rest);
  for (int v = 0; v < rest.num_vertices; ++v)
    if (!irregular[v] && !fans.one_fan(v)) irregular[v] = 1;
  return irregular;
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
