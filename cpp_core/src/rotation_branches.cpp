// Choice of rotation-log branches along a minimum spanning tree of the triangle adjacency.
#include "rotation_branches.h"

#include <cmath>
#include <functional>
#include <queue>
#include <tuple>
#include <vector>

#include "safe_basins.h"

namespace meshik {

namespace {

constexpr double kPi = 3.1415926535897932384626433832795;
constexpr double kTwoPi = 2 * kPi;
// Below this angle a rotation is the identity to working precision and its axis is meaningless.
constexpr double kIdentityAngle = 1e-12;
// The branch of a principal log p (angle theta, axis a) closest to a reference r is p itself
// when |a . r - theta| < pi (the best k is then 0). Below this bound that holds with room for
// the rounding of the norms, the dot product and the division (a few ulps of pi).
constexpr double kSafeOffset = kPi - 1e-9;
// Below this angle the axis is not trusted: the bound is taken as theta + |r|.
constexpr double kSmallAngle = 1e-6;
// Distance thresholds of the nested basins (safe_basins.h) in which the spanning tree is
// skipped where it cannot change a branch. The distance is about the squared angle between
// neighbouring rotations; on the elephant's examples about a third, then a hundredth of the
// edges are longer than these. Any increasing values give the same branches, only the time
// differs (on the elephant these two beat four levels from 1e-4 to 3e-2, and one at 1).
const std::vector<double> kBasinThresholds = {1e-3, 1e-1};

// Whether closest_log_branch keeps both principal logs (angles angle_a, angle_b) principal, each
// taken with the other as the reference.
bool keeps_principal(const Eigen::Vector3d& a, double angle_a, const Eigen::Vector3d& b, double angle_b) {
  if (angle_a + angle_b < kSafeOffset) return true;  // |a . r - theta| <= theta + |r|
  if (angle_a < kSmallAngle || angle_b < kSmallAngle) return false;
  const double dot = a.dot(b);
  return std::abs(dot / angle_a - angle_a) < kSafeOffset && std::abs(dot / angle_b - angle_b) < kSafeOffset;
}

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
  if (k == 0.0) return principal;
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

std::vector<int> choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                                const TriangleComponents& components, const double* distances,
                                                Eigen::Vector3d* logs) {
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  // The unsafe edges, along which a branch could leave the principal one (both logs principal):
  // one end at least is turned by half the safe offset or more.
  // The least rotated triangle of each component (the least index among equals) is its root.
  std::vector<int> unsafe, root(components.count, -1);
  std::vector<double> root_angle(components.count);
  for (int a = 0; a < m; ++a) {
    const double angle_a = logs[a].norm();
    const int c = components.component_of[a];
    if (root[c] < 0 || angle_a < root_angle[c]) root[c] = a, root_angle[c] = angle_a;
    if (angle_a < 0.5 * kSafeOffset) continue;
    for (int s = adjacency.start[a]; s < adjacency.start[a + 1]; ++s) {
      const int b = adjacency.neighbour[s];
      if (!keeps_principal(logs[a], angle_a, logs[b], logs[b].norm())) unsafe.insert(unsafe.end(), {a, b});
    }
  }
  std::vector<int> moved;
  if (unsafe.empty()) return moved;  // every log keeps its principal branch, whatever the tree
  SafeBasins basins = safe_basins(adjacency, distances, kBasinThresholds, unsafe);
  // Only the components with an unsafe edge grow a tree (from their roots, which keep their
  // principal logs): the others keep all their principal logs.
  std::vector<char> grows(components.count, 0);
  for (size_t p = 0; p < unsafe.size(); p += 2) grows[components.component_of[unsafe[p]]] = 1;

  // Prim's algorithm: grow a tree from each root, always across the edge whose two rotations
  // are closest (ties: the least tree triangle, then the least new one), so that a branch is only
  // ever copied between nearly equal rotations. A basin is added whole before any edge leaving it
  // (safe_basins.h): where the tree enters a safe basin from a principal log across a safe edge,
  // every triangle of it keeps its principal log whatever the tree inside, and the basin joins
  // at once. Entered otherwise, its triangles are marked (safe level -1) to be added one by one.
  enum : char { kOutside, kPrincipal, kOtherBranch };
  std::vector<char> state(m, kOutside);
  // The edges offered from the tree, (distance, tree triangle, triangle) least first; those whose
  // triangle has joined since are passed over when they come up.
  using Edge = std::tuple<double, int, int>;
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> frontier;
  const SafeBasinMembers members = safe_basin_members(adjacency, basins);
  // Raw pointers: the loops' stores could otherwise alias the vectors' own fields.
  const int* start = adjacency.start.data();
  const int* neighbour = adjacency.neighbour.data();
  const signed char* edge_level = basins.edge_level.data();
  char* in_state = state.data();
  const auto offer_edges_of = [&](int j) {
    for (int s = start[j]; s < start[j + 1]; ++s)
      if (in_state[neighbour[s]] == kOutside) frontier.emplace(distances[s], j, neighbour[s]);
  };
  // Adds the basin of x at `level` to the tree with its principal logs (x outside the tree, the
  // basin not entered), and offers the edges leaving it (those of a higher level to triangles
  // outside: the links inside the basin are shorter).
  const auto join_basin = [&](int x, int level) {
    const int* first = members.member.data() + members.start[members.basin_of[x]];
    const int* last = members.member.data() + members.start[members.basin_of[x] + 1];
    for (const int* p = first; p != last; ++p) in_state[*p] = kPrincipal;
    for (const int* p = first; p != last; ++p)
      for (int s = start[*p]; s < start[*p + 1]; ++s)
        if (edge_level[s] > level && in_state[neighbour[s]] == kOutside)
          frontier.emplace(distances[s], *p, neighbour[s]);
  };
  // Marks the triangles of x's basin (x outside the tree, the basin not entered) to be added one
  // by one.
  const auto unmark_basin = [&](int x) {
    const int basin = members.basin_of[x];
    for (int p = members.start[basin]; p < members.start[basin + 1]; ++p) basins.safe_level[members.member[p]] = -1;
  };
  // Adds x to the tree, reached from `from` (-1 for a root).
  const auto join = [&](int x, int from) {
    const int level = basins.safe_level[x];
    if (level >= 0) {
      // x enters its basin at `level`: were the basin entered, x would be in the tree or marked.
      if (from < 0 ||
          (state[from] == kPrincipal && keeps_principal(logs[from], logs[from].norm(), logs[x], logs[x].norm()))) {
        join_basin(x, level);
        return;
      }
      unmark_basin(x);
    }
    const Eigen::Vector3d principal = logs[x];
    if (from >= 0) logs[x] = closest_log_branch(principal, logs[from]);
    state[x] = logs[x] == principal ? kPrincipal : kOtherBranch;
    if (state[x] == kOtherBranch) moved.push_back(x);
    offer_edges_of(x);
  };
  for (int c = 0; c < components.count; ++c) {
    if (!grows[c]) continue;
    join(root[c], -1);
    while (!frontier.empty()) {
      const auto [distance, from, to] = frontier.top();
      frontier.pop();
      if (state[to] == kOutside) join(to, from);
    }
  }
  return moved;
}

void choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                    const std::vector<Eigen::Matrix3d>& rotations,
                                    std::vector<Eigen::Vector3d>& logs) {
  std::vector<double> distances(adjacency.neighbour.size());
  rotation_edge_distances(adjacency, rotations.data(), 0, static_cast<int>(rotations.size()), distances.data());
  choose_consistent_log_branches(adjacency, triangle_components(adjacency), distances.data(), logs.data());
}

}  // namespace meshik
