// Per-pose error quadrics (see pose_quadrics.h).
#include "pose_quadrics.h"

#include <algorithm>
#include <array>
#include <unordered_set>

namespace meshik {
namespace decimation {

namespace {

// Takes the triangles; returns, for every directed edge a -> b whose reverse no triangle has (an
// open border), (a, b, triangle id), in triangle order.
std::vector<std::array<int, 3>> border_edges(const int* triangles, int num_triangles, int num_vertices) {
  std::unordered_set<long long> directed;
  const auto key = [&](int a, int b) { return static_cast<long long>(a) * num_vertices + b; };
  for (int t = 0; t < num_triangles; ++t)
    for (int k = 0; k < 3; ++k) directed.insert(key(triangles[3 * t + k], triangles[3 * t + (k + 1) % 3]));
  std::vector<std::array<int, 3>> border;
  for (int t = 0; t < num_triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[3 * t + k], b = triangles[3 * t + (k + 1) % 3];
      if (!directed.count(key(b, a))) border.push_back({a, b, t});
    }
  }
  return border;
}

}  // namespace

PoseQuadrics::PoseQuadrics(const int* triangles, int num_triangles, const PoseTable& poses, int threads)
    : poses_(poses), quadrics_(static_cast<size_t>(poses.num_vertices()) * poses.count()) {
  const std::vector<std::array<int, 3>> border = border_edges(triangles, num_triangles, poses.num_vertices());
  (void)threads;  // unused without OpenMP
  // one pose per thread: each quadric adds its planes in triangle order whatever the thread count
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int p = 0; p < poses.count(); ++p) {
    for (int t = 0; t < num_triangles; ++t) {
      const int* v = triangles + 3 * static_cast<size_t>(t);
      add_triangle_plane(poses.at(p, v[0]), poses.at(p, v[1]), poses.at(p, v[2]), at(v[0], p), at(v[1], p),
                         at(v[2], p));
    }
    for (const auto& edge : border) {
      const int* v = triangles + 3 * static_cast<size_t>(edge[2]);
      add_border_plane(poses.at(p, edge[0]), poses.at(p, edge[1]), poses.at(p, v[0]), poses.at(p, v[1]),
                       poses.at(p, v[2]), at(edge[0], p), at(edge[1], p));
    }
  }
}

double PoseQuadrics::collapse_error(int v0, int v1) const {
  double error = 0.0;
  for (int p = 0; p < poses_.count(); ++p) {
    Quadric q = at(v0, p);
    q += at(v1, p);
    error += q.error(poses_.at(p, v1));
  }
  return std::max(error, 0.0);
}

void PoseQuadrics::merge(int v0, int v1) {
  for (int p = 0; p < poses_.count(); ++p) at(v1, p) += at(v0, p);
}

}  // namespace decimation
}  // namespace meshik
