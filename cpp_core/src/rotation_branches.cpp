// Choice of rotation-log branches along a minimum spanning tree of the triangle adjacency.
#include "rotation_branches.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <tuple>
#include <vector>

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
                                    const std::vector<Eigen::Matrix3d>& rotations,
                                    std::vector<Eigen::Vector3d>& logs) {
  const int m = static_cast<int>(logs.size());
  // Prim's algorithm: grow a tree from the least rotated triangle of each component, always
  // across the edge whose two rotations are closest (3 - trace(R_a^T R_b), monotone in the angle
  // between them), so that a branch is only ever copied between nearly equal rotations.
  using Edge = std::tuple<double, int, int>;  // (distance, from, to)
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> frontier;
  std::vector<char> in_tree(m, 0);
  std::vector<int> order(m);
  for (int j = 0; j < m; ++j) order[j] = j;
  std::vector<double> angle(m);
  for (int j = 0; j < m; ++j) angle[j] = logs[j].norm();
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return angle[a] < angle[b]; });
  auto add_edges_of = [&](int from) {
    in_tree[from] = 1;
    for (int s = adjacency.start[from]; s < adjacency.start[from + 1]; ++s) {
      const int to = adjacency.neighbour[s];
      if (!in_tree[to])
        frontier.emplace(3.0 - (rotations[from].transpose() * rotations[to]).trace(), from, to);
    }
  };
  for (int root : order) {
    if (in_tree[root]) continue;
    add_edges_of(root);
    while (!frontier.empty()) {
      const auto [distance, from, to] = frontier.top();
      frontier.pop();
      if (in_tree[to]) continue;
      logs[to] = closest_log_branch(logs[to], logs[from]);
      add_edges_of(to);
    }
  }
}

}  // namespace meshik
