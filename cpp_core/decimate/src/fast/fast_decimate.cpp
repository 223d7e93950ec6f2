// The fast pose-aware decimator (decimate_example_set_fast in meshik/decimate.h): half-edge
// collapses in order of the quadric error summed over every pose, from a heap whose entries are
// checked only when popped (fast quadric simplification's lazy approach), no OpenMesh.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

#include "../triangle_check.h"
#include "../triangle_soundness.h"
#include "collapse_mesh.h"
#include "../distance_guard.h"
#include "meshik/decimate.h"
#include "pose_quadrics.h"
#include "pose_table.h"
#include "thread_count.h"

namespace meshik {
namespace {

using decimation::CollapseMesh;
using decimation::PoseQuadrics;
using decimation::PoseTable;
using FastDistanceGuard = decimation::DistanceGuard<CollapseMesh, PoseTable>;
using decimation::Vec3;

// A half-edge collapse v0 -> v1 waiting in the heap, valid while both vertices' stamps (bumped
// when their quadrics change) are unchanged.
struct Candidate {
  double error;
  int v0, v1;
  unsigned stamp0, stamp1;
};

// Heap order: the least error first, ties by vertex ids (the same order on every run).
struct Later {
  bool operator()(const Candidate& a, const Candidate& b) const {
    if (a.error != b.error) return a.error > b.error;
    if (a.v0 != b.v0) return a.v0 > b.v0;
    return a.v1 > b.v1;
  }
};

using CandidateHeap = std::priority_queue<Candidate, std::vector<Candidate>, Later>;

// Whether moving v0 onto v1 leaves every triangle around v0 (but those with v1, which vanish)
// non-degenerate and turned by less than the limit (min_cos: its cosine), in every pose.
bool keeps_triangles_sound(const CollapseMesh& mesh, const PoseTable& poses, int v0, int v1, double min_cos) {
  for (int t : mesh.triangles_around(v0)) {
    const std::array<int, 3>& c = mesh.corners(t);
    if (c[0] == v1 || c[1] == v1 || c[2] == v1) continue;
    const int moved = c[0] == v0 ? 0 : (c[1] == v0 ? 1 : 2);
    for (int p = 0; p < poses.count(); ++p) {
      const std::array<Vec3, 3> corner = {poses.at(p, c[0]), poses.at(p, c[1]), poses.at(p, c[2])};
      if (!decimation::moved_triangle_is_sound(corner, moved, poses.at(p, v1), min_cos)) return false;
    }
  }
  return true;
}

// The decimation loop's state: mesh, quadrics, guard, heap and per-vertex stamps.
class FastDecimator {
 public:
  FastDecimator(const MeshView& rest, const PoseTable& poses, const std::vector<int>& locked, double min_cos,
                int threads)
      : poses_(poses),
        mesh_(rest.triangles, rest.num_triangles, rest.num_vertices),
        quadrics_(rest.triangles, rest.num_triangles, poses, threads),
        guard_(mesh_, poses),
        locked_(decimation::irregular_vertices(rest)),
        stamp_(rest.num_vertices, 0),
        refused_(rest.num_vertices),
        parent_(rest.num_vertices),
        min_cos_(min_cos),
        threads_(threads) {
    for (int v : locked) locked_[v] = 1;
    for (int v = 0; v < rest.num_vertices; ++v) parent_[v] = v;
  }

  // Collapses until at most `target` triangles remain under the bound (relaxed as DistanceBound
  // says while short of the target); fills result's bound, relaxations and worst_distance.
  void run(int target, const DistanceBound& bound, DecimationResult& result) {
    result.bound = bound.max_distance;
    guard_.set_bound(result.bound);
    fill_heap();
    while (mesh_.remaining_triangles() > target) {
      if (heap_.empty()) {
        if (std::isinf(result.bound)) break;  // no legal collapse is left
        ++result.relaxations;
        result.bound = result.relaxations > bound.max_relaxations
                           ? std::numeric_limits<double>::infinity()
                           : std::max(result.bound * bound.relax_factor, guard_.least_refused());
        guard_.set_bound(result.bound);
        fill_heap();
        continue;
      }
      const Candidate c = heap_.top();
      heap_.pop();
      if (!mesh_.vertex_alive(c.v0) || !mesh_.vertex_alive(c.v1) || c.stamp0 != stamp_[c.v0] ||
          c.stamp1 != stamp_[c.v1])
        continue;
      if (mesh_.collapse_keeps_manifold(c.v0, c.v1) && keeps_triangles_sound(mesh_, poses_, c.v0, c.v1, min_cos_) &&
          guard_.allows(c.v0, c.v1))
        collapse(c.v0, c.v1);
      else
        refused_[c.v0].push_back(c.v1);  // tried again when v0's neighbourhood changes
    }
    result.worst_distance = guard_.worst_distance();
  }

  // Fills the kept vertices, triangles and vertex map of the result.
  void write(DecimationResult& result) const {
    const int n = mesh_.num_vertices();
    std::vector<int> new_index(n, -1);
    for (int v = 0; v < n; ++v) {
      if (!mesh_.vertex_alive(v)) continue;
      new_index[v] = static_cast<int>(result.kept_vertices.size());
      result.kept_vertices.push_back(v);
    }
    for (int t = 0; t < mesh_.num_triangles(); ++t)
      if (mesh_.triangle_alive(t))
        for (int v : mesh_.corners(t)) result.triangles.push_back(new_index[v]);
    result.vertex_map.resize(n);
    for (int v = 0; v < n; ++v) {
      int root = v;
      while (parent_[root] != root) root = parent_[root];
      result.vertex_map[v] = new_index[root];
    }
  }

 private:
  // Pushes the half-edge collapse v0 -> v1 (unless v0 is locked) with the current stamps.
  void push(int v0, int v1) {
    if (!locked_[v0]) heap_.push({quadrics_.collapse_error(v0, v1), v0, v1, stamp_[v0], stamp_[v1]});
  }

  // A fresh heap of every half-edge out of a free vertex (errors computed on the threads).
  void fill_heap() {
    std::vector<std::vector<Candidate>> from(mesh_.num_vertices());
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads_)
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      if (locked_[v] || !mesh_.vertex_alive(v)) continue;
      for (int n : mesh_.neighbours(v))
        from[v].push_back({quadrics_.collapse_error(v, n), v, n, stamp_[v], stamp_[n]});
    }
    for (auto& list : refused_) list.clear();
    std::vector<Candidate> all;
    for (const auto& list : from) all.insert(all.end(), list.begin(), list.end());
    heap_ = CandidateHeap(Later(), std::move(all));
  }

  // Collapses v0 onto v1, renews the collapses along v1's edges (whose quadric changed) and pushes
  // again those refused from v1's neighbours (whose triangles or attached points changed).
  void collapse(int v0, int v1) {
    guard_.before_collapse(v0);
    mesh_.collapse(v0, v1);
    quadrics_.merge(v0, v1);
    parent_[v0] = v1;
    guard_.after_collapse(v1);
    ++stamp_[v1];
    refused_[v0].clear();
    refused_[v1].clear();
    for (int n : mesh_.neighbours(v1)) {
      push(v1, n);
      push(n, v1);
      for (int other : refused_[n])
        if (other != v1 && mesh_.vertex_alive(other)) push(n, other);
      refused_[n].clear();
    }
  }

  const PoseTable& poses_;
  CollapseMesh mesh_;
  PoseQuadrics quadrics_;
  FastDistanceGuard guard_;
  std::vector<char> locked_;
  std::vector<unsigned> stamp_;
  std::vector<std::vector<int>> refused_;  // per vertex: neighbours it was refused a collapse onto
  std::vector<int> parent_;
  CandidateHeap heap_;
  double min_cos_;
  int threads_;
};

}  // namespace

DecimationResult decimate_example_set_fast(const MeshView& rest, const std::vector<const double*>& examples,
                                           const std::vector<int>& locked, int target_triangles,
                                           double max_normal_change_degrees, const DistanceBound& bound, int threads) {
  decimation::check_request(rest.num_vertices, locked, target_triangles, bound);
  decimation::check_corners(rest);
  threads = decimation::resolve_threads(threads);
  std::vector<const double*> positions(1, rest.vertices);
  positions.insert(positions.end(), examples.begin(), examples.end());
  const PoseTable poses(positions, rest.num_vertices, threads);
  FastDecimator decimator(rest, poses, locked, std::cos(max_normal_change_degrees * M_PI / 180.0), threads);
  DecimationResult result;
  decimator.run(target_triangles, bound, result);
  decimator.write(result);
  return result;
}

}  // namespace meshik
