// Breadth-first choice of rotation-log branches over the triangle adjacency.
#include "rotation_branches.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshik {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
// Below this angle a rotation is the identity to working precision and its axis is meaningless.
constexpr double kIdentityAngle = 1e-12;

}  // namespace

Eigen::Vector3d closest_log_branch(const Eigen::Vector3d& principal,
                                   const Eigen::Vector3d& reference) {
  const double theta = principal.norm();
  if (theta < kIdentityAngle) {
    // The identity's logs are 2 pi k a for any axis a: take the reference's axis.
    const double length = reference.norm();
    const double turns = std::round(length / kTwoPi);
    if (turns == 0.0) return principal;
    return principal + (turns * kTwoPi / length) * reference;
  }
  const Eigen::Vector3d axis = principal / theta;
  // |(theta + 2 pi k) axis - reference| is smallest when theta + 2 pi k is closest to
  // axis . reference.
  const double k = std::round((axis.dot(reference) - theta) / kTwoPi);
  return (theta + kTwoPi * k) * axis;
}

void choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                    std::vector<Eigen::Vector3d>& logs) {
  const int m = static_cast<int>(logs.size());
  std::vector<int> order(m);
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> angle(m);
  for (int j = 0; j < m; ++j) angle[j] = logs[j].norm();
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return angle[a] < angle[b]; });

  std::vector<char> visited(m, 0);
  std::vector<int> queue;
  queue.reserve(m);
  for (int root : order) {
    if (visited[root]) continue;
    visited[root] = 1;
    queue.clear();
    queue.push_back(root);
    for (size_t head = 0; head < queue.size(); ++head) {
      const int from = queue[head];
      for (int s = adjacency.start[from]; s < adjacency.start[from + 1]; ++s) {
        const int to = adjacency.neighbour[s];
        if (visited[to]) continue;
        visited[to] = 1;
        logs[to] = closest_log_branch(logs[to], logs[from]);
        queue.push_back(to);
      }
    }
  }
}

}  // namespace meshik
