// Choice of rotation-log branches along a minimum spanning tree of the triangle adjacency.
#include "rotation_branches.h"

#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

namespace meshik {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
// Below this angle a rotation is the identity to working precision and its axis is meaningless.
constexpr double kIdentityAngle = 1e-12;

// Prim's frontier: the triangles next to the tree, each with its best edge into the tree
// (distance, tree triangle), in a binary heap ordered by (distance, from, to), position-indexed
// so an edge found shorter lowers its triangle's key in place. The keys live in the heap's
// entries, so sifting reads no other array.
class Frontier {
 public:
  explicit Frontier(int m) : position_(m, -1) {}

  bool empty() const { return heap_.empty(); }

  // Offers the edge (distance, from) to triangle `to`, not in the tree: kept if it is the
  // triangle's first or better than its current edge.
  void offer(int to, double distance, int from) {
    const Entry entry{distance, from, to};
    int at = position_[to];
    if (at < 0) {
      at = static_cast<int>(heap_.size());
      heap_.push_back(entry);
    } else if (!less(entry, heap_[at])) {
      return;
    }
    sift_up(at, entry);
  }

  // Removes the triangle with the least (distance, from, to); returns it and its tree neighbour.
  std::pair<int, int> pop() {
    const Entry top = heap_.front();
    position_[top.to] = -1;
    const Entry last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) sift_down(0, last);
    return {top.to, top.from};
  }

 private:
  struct Entry {
    double distance;
    int from, to;
  };
  static bool less(const Entry& a, const Entry& b) {
    return std::tie(a.distance, a.from, a.to) < std::tie(b.distance, b.from, b.to);
  }
  void place(int at, const Entry& entry) {
    heap_[at] = entry;
    position_[entry.to] = at;
  }
  // Puts entry at `at` or above.
  void sift_up(int at, const Entry& entry) {
    while (at > 0) {
      const int parent = (at - 1) / 2;
      if (!less(entry, heap_[parent])) break;
      place(at, heap_[parent]);
      at = parent;
    }
    place(at, entry);
  }
  // Puts entry at `at` or below.
  void sift_down(int at, const Entry& entry) {
    const int size = static_cast<int>(heap_.size());
    for (;;) {
      int child = 2 * at + 1;
      if (child >= size) break;
      if (child + 1 < size && less(heap_[child + 1], heap_[child])) ++child;
      if (!less(heap_[child], entry)) break;
      place(at, heap_[child]);
      at = child;
    }
    place(at, entry);
  }

  std::vector<Entry> heap_;
  std::vector<int> position_;  // the heap slot of each triangle, -1 when not in the heap
};

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

double rotation_distance(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to) {
  return 3.0 - (from.transpose() * to).trace();
}

void rotation_edge_distances(const TriangleAdjacency& adjacency, const Eigen::Matrix3d* rotations, int first,
                             int last, double* distances) {
  for (int j = first; j < last; ++j)
    for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s)
      distances[s] = rotation_distance(rotations[j], rotations[adjacency.neighbour[s]]);
}

void choose_consistent_log_branches(const TriangleAdjacency& adjacency, const double* distances,
                                    std::vector<Eigen::Vector3d>& logs) {
  const int m = static_cast<int>(logs.size());
  // Prim's algorithm: grow a tree from the least rotated triangle of each component (least
  // principal angle, then least index), always across the edge whose two rotations are closest
  // (ties: the least tree triangle, then the least new one), so that a branch is only ever
  // copied between nearly equal rotations.
  std::vector<char> seen(m, 0);
  std::vector<int> component;
  Frontier frontier(m);
  for (int start = 0; start < m; ++start) {
    if (seen[start]) continue;
    // The component of start (breadth first) and its root.
    component.assign(1, start);
    seen[start] = 1;
    int root = start;
    double root_angle = logs[start].norm();
    for (size_t head = 0; head < component.size(); ++head) {
      const int j = component[head];
      const double angle = logs[j].norm();
      if (std::tie(angle, j) < std::tie(root_angle, root)) root = j, root_angle = angle;
      for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s)
        if (!seen[adjacency.neighbour[s]]) {
          seen[adjacency.neighbour[s]] = 1;
          component.push_back(adjacency.neighbour[s]);
        }
    }
    int joined = root;
    for (;;) {
      for (int s = adjacency.start[joined]; s < adjacency.start[joined + 1]; ++s) {
        const int to = adjacency.neighbour[s];
        if (seen[to] != 2) frontier.offer(to, distances[s], joined);
      }
      seen[joined] = 2;  // in the tree
      if (frontier.empty()) break;
      const auto [to, from] = frontier.pop();
      logs[to] = closest_log_branch(logs[to], logs[from]);
      joined = to;
    }
  }
}

void choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                    const std::vector<Eigen::Matrix3d>& rotations,
                                    std::vector<Eigen::Vector3d>& logs) {
  std::vector<double> distances(adjacency.neighbour.size());
  rotation_edge_distances(adjacency, rotations.data(), 0, static_cast<int>(rotations.size()), distances.data());
  choose_consistent_log_branches(adjacency, distances.data(), logs);
}

}  // namespace meshik
