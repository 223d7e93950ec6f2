// SO(3) maps, their derivatives, the vectorised sine/cosine, the polar decomposition and the
// choice of rotation-log branches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <random>
#include <tuple>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "lane_math.h"
#include "mesh_topology.h"
#include "polar_batch.h"
#include "rotation_branches.h"
#include "safe_basins.h"
#include "so3.h"
#include "triangle_frames.h"

namespace {

using meshik::polar_decomposition;
using meshik::so3_exp;
using meshik::so3_log;

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Rotation vectors whose angles cover 0, tiny, moderate, the Taylor threshold and the
// neighbourhood of pi.
std::vector<Eigen::Vector3d> test_rotation_vectors() {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> vectors;
  for (double angle : {0.0, 1e-12, 1e-8, 1e-4, 0.05, 0.0999, 0.1, 0.1001, 0.7, 1.5, 2.5, 3.0,
                       kPi - 1e-3, kPi - 1e-6, kPi - 1e-9}) {
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d axis = Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
      vectors.push_back(angle * axis);
    }
  }
  return vectors;
}

TEST(So3, ExpMatchesAngleAxisAndLogInvertsIt) {
  for (const Eigen::Vector3d& phi : test_rotation_vectors()) {
    const double angle = phi.norm();
    const Eigen::Matrix3d expected =
        angle > 0 ? Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d r = so3_exp(phi);
    EXPECT_LT((r - expected).norm(), 1e-14) << "angle " << angle;
    EXPECT_LT((so3_log(r) - phi).norm(), angle > kPi - 1e-5 ? 1e-7 : 1e-13) << "angle " << angle;
  }
}

TEST(So3, LogAtExactlyPiAndBeyondPiIsPrincipal) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 2) / 3.0;
  const Eigen::Vector3d at_pi = so3_log(Eigen::AngleAxisd(kPi, axis).toRotationMatrix());
  EXPECT_NEAR(at_pi.norm(), kPi, 1e-12);
  EXPECT_NEAR(std::abs(at_pi.normalized().dot(axis)), 1.0, 1e-12);
  // A rotation by 4 (> pi) about axis is one by 2 pi - 4 about -axis.
  const Eigen::Vector3d beyond = so3_log(so3_exp(4.0 * axis));
  EXPECT_LT((beyond - (4.0 - 2.0 * kPi) * axis).norm(), 1e-13);
}

TEST(So3, LeftJacobianIsTheDerivativeOfExp) {
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  for (const Eigen::Vector3d& phi : test_rotation_vectors()) {
    const Eigen::Vector3d u(normal(random), normal(random), normal(random));
    const double h = 1e-6;
    // d/dt exp(phi + t u) exp(phi)^T at t = 0 is [J_l(phi) u]_x.
    const Eigen::Matrix3d derivative =
        (so3_exp(phi + h * u) - so3_exp(phi - h * u)) / (2 * h) * so3_exp(phi).transpose();
    EXPECT_LT((derivative - cross_matrix(meshik::so3_left_jacobian_times(phi, u))).norm(), 1e-8)
        << "angle " << phi.norm();
  }
}

TEST(So3, RodriguesCoefficientsAndDerivativesAreAccurateOnBothSidesOfTheTaylorSwitch) {
  for (double theta : {0.03, 0.0999999, 0.1, 0.1000001, 0.5, 2.0, 3.1, 5.0, 9.0}) {
    // References in long double (its 64-bit mantissa absorbs the cancellations for these angles).
    const long double t = theta, t2 = t * t;
    const long double a = std::sin(t) / t, b = (1 - std::cos(t)) / t2, c = (t - std::sin(t)) / (t2 * t);
    const long double db = (a - 2 * b) / (2 * t2), dc = (b - 3 * c) / (2 * t2);
    const meshik::RodriguesCoefficients k = meshik::rodrigues_coefficients(theta * theta);
    EXPECT_NEAR(k.a, static_cast<double>(a), 4e-16) << theta;
    EXPECT_NEAR(k.b, static_cast<double>(b), 4e-16) << theta;
    // (t - sin t) / t^3 cancels just above the switch to the series (about 3 digits at 0.1).
    EXPECT_NEAR(k.c, static_cast<double>(c), theta < 0.5 ? 1e-13 : 4e-16) << theta;
    const double theta_squared = theta * theta;
    double k_db, k_dc;
    meshik::rodrigues_derivative_lanes<1>(&theta_squared, &k.a, &k.b, &k.c, &k_db, &k_dc);
    EXPECT_NEAR(k_db, static_cast<double>(db), 1e-12) << theta;
    EXPECT_NEAR(k_dc, static_cast<double>(dc), 1e-11) << theta;
  }
  // At the identity: the series' constant terms.
  const meshik::RodriguesCoefficients zero = meshik::rodrigues_coefficients(0.0);
  EXPECT_EQ(zero.a, 1.0);
  EXPECT_EQ(zero.b, 0.5);
  EXPECT_EQ(zero.c, 1.0 / 6.0);
}

TEST(So3, VectorisedSineAndCosineMatchTheLibrary) {
  constexpr int kLanes = 8;
  double x[kLanes], s[kLanes], c[kLanes];
  for (int start = 0; start < 4000; start += kLanes) {
    for (int l = 0; l < kLanes; ++l) x[l] = (start + l) * 0.01 + 1e-3 * l;
    meshik::sin_cos_lanes<kLanes>(x, s, c);
    for (int l = 0; l < kLanes; ++l) {
      EXPECT_NEAR(s[l], std::sin(x[l]), 4e-16) << x[l];
      EXPECT_NEAR(c[l], std::cos(x[l]), 4e-16) << x[l];
    }
  }
}

// The single-precision lanes (the curvature pass's) to within a few float roundings.
TEST(So3, SinglePrecisionLanesMatchTheLibrary) {
  constexpr int kLanes = 16;
  float x[kLanes], s[kLanes], c[kLanes], a[kLanes], b[kLanes], cc[kLanes];
  for (int start = 0; start < 1000; start += kLanes) {
    for (int l = 0; l < kLanes; ++l) x[l] = static_cast<float>((start + l) * 0.01 + 1e-3 * l);
    meshik::sin_cos_lanes<kLanes>(x, s, c);
    for (int l = 0; l < kLanes; ++l) {
      EXPECT_NEAR(s[l], std::sin(static_cast<double>(x[l])), 4e-7) << x[l];
      EXPECT_NEAR(c[l], std::cos(static_cast<double>(x[l])), 4e-7) << x[l];
    }
    float theta_squared[kLanes];
    for (int l = 0; l < kLanes; ++l) theta_squared[l] = x[l] * x[l] * 0.1f;
    meshik::rodrigues_lanes<kLanes>(theta_squared, a, b, cc);
    for (int l = 0; l < kLanes; ++l) {
      const meshik::RodriguesCoefficients exact = meshik::rodrigues_coefficients(theta_squared[l]);
      EXPECT_NEAR(a[l], exact.a, 1e-6) << theta_squared[l];
      EXPECT_NEAR(b[l], exact.b, 1e-6) << theta_squared[l];
      EXPECT_NEAR(cc[l], exact.c, 1e-5 * exact.c) << theta_squared[l];
      float db, dc;
      meshik::rodrigues_derivative_lanes<1>(&theta_squared[l], &a[l], &b[l], &cc[l], &db, &dc);
      const double t2 = theta_squared[l];
      double exact_db, exact_dc;
      meshik::rodrigues_derivative_lanes<1>(&t2, &exact.a, &exact.b, &exact.c, &exact_db, &exact_dc);
      EXPECT_NEAR(db, exact_db, 1e-4 * std::abs(exact_db)) << theta_squared[l];
      EXPECT_NEAR(dc, exact_dc, 1e-4 * std::abs(exact_dc)) << theta_squared[l];
    }
  }
}

TEST(So3, PolarDecompositionIsProperEvenForReflectionsAndDegenerateMatrices) {
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Matrix3d> matrices;
  for (int i = 0; i < 20; ++i) {
    Eigen::Matrix3d t;
    for (int e = 0; e < 9; ++e) t(e) = normal(random);
    matrices.push_back(t);
  }
  matrices.push_back(Eigen::Vector3d(1, 1, -1).asDiagonal());               // a reflection
  matrices.push_back(Eigen::Vector3d(2, 0.5, 0).asDiagonal());              // rank 2 (a flat triangle)
  matrices.push_back(Eigen::Matrix3d::Zero());                               // rank 0
  matrices.push_back(so3_exp(Eigen::Vector3d(0, 0, kPi - 1e-9)) * 1.5);    // near a half turn
  for (const Eigen::Matrix3d& t : matrices) {
    const meshik::PolarDecomposition p = polar_decomposition(t);
    EXPECT_LT((p.rotation * p.rotation.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-13);
    EXPECT_NEAR(p.rotation.determinant(), 1.0, 1e-13);
    EXPECT_LT((p.stretch - p.stretch.transpose()).norm(), 1e-13);
    EXPECT_LT((p.rotation * p.stretch - t).norm(), 1e-13 * std::max(1.0, t.norm()));
  }
}

TEST(RotationBranches, ClosestBranchFollowsTheReference) {
  const Eigen::Vector3d axis(0, 0, 1);
  // Principal log 0.9 pi about axis; a reference at -1.1 pi about axis (the same rotation).
  const Eigen::Vector3d principal = 0.9 * kPi * axis;
  EXPECT_LT((meshik::closest_log_branch(principal, -1.05 * kPi * axis) - (-1.1 * kPi) * axis).norm(), 1e-12);
  EXPECT_LT((meshik::closest_log_branch(principal, 0.8 * kPi * axis) - principal).norm(), 1e-15);
  EXPECT_LT((meshik::closest_log_branch(principal, 2.7 * kPi * axis) - 2.9 * kPi * axis).norm(), 1e-12);
  // The identity next to a full turn about x becomes that full turn.
  const Eigen::Vector3d turn = meshik::closest_log_branch(Eigen::Vector3d::Zero(), Eigen::Vector3d(6.2, 0, 0));
  EXPECT_LT((turn - Eigen::Vector3d(2 * kPi, 0, 0)).norm(), 1e-12);
}

TEST(RotationBranches, ATwistBeyondAHalfTurnKeepsContinuousLogs) {
  // A strip of triangles (a path in the adjacency) rotating about z from 0 to 1.8 pi.
  const int m = 60;
  meshik::TriangleAdjacency path;
  path.start.push_back(0);
  for (int j = 0; j < m; ++j) {
    if (j > 0) path.neighbour.push_back(j - 1);
    if (j + 1 < m) path.neighbour.push_back(j + 1);
    path.start.push_back(static_cast<int>(path.neighbour.size()));
  }
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::Vector3d> logs;
  for (int j = 0; j < m; ++j) {
    rotations.push_back(so3_exp(Eigen::Vector3d(0, 0, 1.8 * kPi * j / (m - 1))));
    logs.push_back(so3_log(rotations.back()));
  }
  int jumps = 0;
  for (int j = 1; j < m; ++j) jumps += (logs[j] - logs[j - 1]).norm() > kPi;
  EXPECT_EQ(jumps, 1);  // the principal logs jump once, at the half turn
  meshik::choose_consistent_log_branches(path, rotations, logs);
  for (int j = 0; j < m; ++j) {
    EXPECT_NEAR(logs[j].z(), 1.8 * kPi * j / (m - 1), 1e-12) << j;
    EXPECT_LT((so3_exp(logs[j]) - rotations[j]).norm(), 1e-12);  // still logs of the same rotations
  }
}

// The branch choice as first written (kept here as the reference): Prim's algorithm with every
// edge pushed into a priority queue of (distance, from, to), roots by a stable sort of the angles.
void reference_log_branches(const meshik::TriangleAdjacency& adjacency, const std::vector<Eigen::Matrix3d>& rotations,
                            std::vector<Eigen::Vector3d>& logs) {
  const int m = static_cast<int>(logs.size());
  using Edge = std::tuple<double, int, int>;
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
      if (!in_tree[to]) frontier.emplace(meshik::rotation_distance(rotations[from], rotations[to]), from, to);
    }
  };
  for (int root : order) {
    if (in_tree[root]) continue;
    add_edges_of(root);
    while (!frontier.empty()) {
      const auto [distance, from, to] = frontier.top();
      frontier.pop();
      if (in_tree[to]) continue;
      logs[to] = meshik::closest_log_branch(logs[to], logs[from]);
      add_edges_of(to);
    }
  }
}

TEST(RotationBranches, PrimsTreeWithAnIndexedFrontierGivesTheReferenceBranchesBitForBit) {
  // A grid of 2 x 40 x 40 triangles in two components, rotations about a few axes near a half
  // turn (branches differ from the principal logs), drawn from a small set so that many
  // distances tie exactly.
  const int side = 40;
  std::vector<int> triangles;
  for (int half = 0; half < 2; ++half)
    for (int r = 0; r < side / 2; ++r)
      for (int c = 0; c < side; ++c) {
        const int base = half * (side / 2 + 1) * (side + 1), v = base + r * (side + 1) + c;
        triangles.insert(triangles.end(), {v, v + 1, v + side + 2, v, v + side + 2, v + side + 1});
      }
  const int m = static_cast<int>(triangles.size() / 3);
  const meshik::TriangleAdjacency adjacency =
      meshik::triangle_adjacency(triangles.data(), m, 2 * (side / 2 + 1) * (side + 1));
  std::mt19937 random(5);
  std::uniform_int_distribution<int> pick(0, 5);
  std::vector<Eigen::Matrix3d> palette;
  for (int p = 0; p < 6; ++p)
    palette.push_back(so3_exp((kPi - 0.05 * p) * Eigen::Vector3d(1.0, 0.1 * p, p % 2 ? 0.2 : -0.2).normalized()));
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<Eigen::Matrix3d> rotations;
    std::vector<Eigen::Vector3d> logs;
    for (int j = 0; j < m; ++j) {
      // Smoothly varying angle plus a palette rotation: ties and near-pi branches both occur.
      const double angle = 0.9 * kPi * (j % (2 * side)) / (2.0 * side) + (trial == 0 ? 0.0 : 0.01 * trial);
      rotations.push_back(palette[pick(random)] * so3_exp(Eigen::Vector3d(0, 0, j % 3 == 0 ? angle : 0.0)));
      logs.push_back(so3_log(rotations.back()));
    }
    std::vector<Eigen::Vector3d> expected = logs;
    reference_log_branches(adjacency, rotations, expected);
    meshik::choose_consistent_log_branches(adjacency, rotations, logs);
    int moved = 0;
    for (int j = 0; j < m; ++j) {
      ASSERT_EQ(logs[j], expected[j]) << "triangle " << j << ", trial " << trial;
      moved += logs[j] != so3_log(rotations[j]);
    }
    EXPECT_GT(moved, 0);  // some branches are not the principal ones
  }
}

// Appends the triangles of a strip of rows x cols quads (two triangles each, a quad's pair
// consecutive, column by column within a row), its vertices numbered from `base`; returns the
// strip's vertex count.
int append_strip(int rows, int cols, int base, std::vector<int>& triangles) {
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int v = base + r * (cols + 1) + c;
      triangles.insert(triangles.end(), {v, v + 1, v + cols + 2, v, v + cols + 2, v + cols + 1});
    }
  return (rows + 1) * (cols + 1);
}

// The edge adjacency of one strip of rows x cols cells (append_strip's triangles).
meshik::TriangleAdjacency strip_adjacency(int rows, int cols) {
  std::vector<int> triangles;
  const int vertices = append_strip(rows, cols, 0, triangles);
  return meshik::triangle_adjacency(triangles.data(), static_cast<int>(triangles.size() / 3), vertices);
}

// Chooses the branches of the logs of `rotations` (one per triangle of the adjacency) with
// choose_consistent_log_branches and with the reference; expects the same bits. Returns the
// chosen logs.
std::vector<Eigen::Vector3d> expect_reference_branches(const meshik::TriangleAdjacency& adjacency,
                                                       const std::vector<Eigen::Matrix3d>& rotations) {
  std::vector<Eigen::Vector3d> logs;
  for (const Eigen::Matrix3d& r : rotations) logs.push_back(so3_log(r));
  std::vector<Eigen::Vector3d> expected = logs;
  reference_log_branches(adjacency, rotations, expected);
  meshik::choose_consistent_log_branches(adjacency, rotations, logs);
  for (size_t j = 0; j < logs.size(); ++j) EXPECT_EQ(logs[j], expected[j]) << "triangle " << j;
  return logs;
}

TEST(RotationBranches, ABasinOfSmallRotationsReachedThroughAFullTurnTakesTheTurnedBranch) {
  // A strip twisted about z: still for 20 columns, turned from 0 to 2 pi - 0.3 over 40, then
  // still again. The last plateau's principal logs (0.3 about -z) are far from any half turn and
  // close to each other (the same rotation up to a small wobble drawn from three, so distances
  // tie), a basin on every level; the tree reaches it through the turn, so its branch is
  // 2 pi - 0.3 about z: it must not be kept principal.
  const int rows = 4, cols = 120;
  const meshik::TriangleAdjacency adjacency = strip_adjacency(rows, cols);
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  const double turned = 2 * kPi - 0.3;
  std::vector<Eigen::Matrix3d> rotations;
  for (int j = 0; j < m; ++j) {
    const int c = (j / 2) % cols;
    const double angle = c < 20 ? 0.0 : c < 60 ? turned * (c - 20) / 40.0 : turned;
    const Eigen::Vector3d wobble = 1e-3 * Eigen::Vector3d(j % 3, (j + 1) % 3, 0.0);
    rotations.push_back(so3_exp(Eigen::Vector3d(0, 0, angle)) * so3_exp(wobble));
  }
  const std::vector<Eigen::Vector3d> logs = expect_reference_branches(adjacency, rotations);
  for (int j = 0; j < m; ++j)
    if ((j / 2) % cols >= 60) EXPECT_NEAR(logs[j].z(), turned, 1e-2) << j;
}

TEST(RotationBranches, ComponentsFarFromHalfTurnsKeepPrincipalLogsAndTheOthersFollowTheReference) {
  // Three strips: small rotations (no log can move: the tree is skipped), a slow turn beyond a
  // half turn with stretches held still (basins entered across the half turn), and rotations
  // either side of a half turn about axes that wobble (principal logs flip between neighbours).
  std::vector<int> triangles;
  int vertices = 0;
  for (int strip = 0; strip < 3; ++strip) vertices += append_strip(6, 60, vertices, triangles);
  const int m = static_cast<int>(triangles.size() / 3);
  const int per_strip = m / 3;
  const meshik::TriangleAdjacency adjacency = meshik::triangle_adjacency(triangles.data(), m, vertices);
  std::mt19937 random(11);
  std::uniform_int_distribution<int> pick(0, 3);
  std::vector<Eigen::Matrix3d> rotations;
  for (int j = 0; j < m; ++j) {
    const int strip = j / per_strip, c = (j / 2) % 60;
    const Eigen::Vector3d wobble = 1e-2 * Eigen::Vector3d(pick(random), pick(random), pick(random));
    if (strip == 0) {
      rotations.push_back(so3_exp(Eigen::Vector3d(0.5 * c / 60.0, 0.2, 0.0) + wobble));
    } else if (strip == 1) {
      const double angle = 1.4 * kPi * std::min(1.0, std::floor(c / 5.0) / 8.0);  // steps of 0.175 pi
      rotations.push_back(so3_exp(angle * Eigen::Vector3d(0.1, 0.0, 1.0).normalized()) * so3_exp(0.1 * wobble));
    } else {
      rotations.push_back(so3_exp((kPi + 0.01 * (pick(random) - 1.5)) * (Eigen::Vector3d(0.0, 0.0, 1.0) + wobble).normalized()));
    }
  }
  const std::vector<Eigen::Vector3d> logs = expect_reference_branches(adjacency, rotations);
  int moved[3] = {0, 0, 0};
  for (int j = 0; j < m; ++j) moved[j / per_strip] += logs[j] != so3_log(rotations[j]);
  EXPECT_EQ(moved[0], 0);
  EXPECT_GT(moved[1], 0);
  EXPECT_GT(moved[2], 0);
}

TEST(RotationBranches, EdgeDistancesAreTheSameBothWaysAndForAnySplitOfTheTriangles) {
  // The basins (safe_basins.h) read each edge from either side: its length must not depend on
  // the side.
  const meshik::TriangleAdjacency adjacency = strip_adjacency(5, 9);
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  std::mt19937 random(13);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Matrix3d> rotations;
  for (int j = 0; j < m; ++j) rotations.push_back(so3_exp(Eigen::Vector3d(normal(random), normal(random), normal(random))));
  std::vector<double> whole(adjacency.neighbour.size(), -1.0), split(adjacency.neighbour.size(), -1.0);
  meshik::rotation_edge_distances(adjacency, rotations.data(), 0, m, whole.data());
  for (int first = m - 7; first > -7; first -= 7)  // ranges from the last down, as threads may
    meshik::rotation_edge_distances(adjacency, rotations.data(), std::max(first, 0), first + 7, split.data());
  EXPECT_EQ(split, whole);
  for (int j = 0; j < m; ++j)
    for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s) {
      const int n = adjacency.neighbour[s];
      // Each entry holds the distance from either end.
      EXPECT_EQ(whole[s], meshik::rotation_distance(rotations[j], rotations[n])) << j << " " << n;
      EXPECT_EQ(whole[s], meshik::rotation_distance(rotations[n], rotations[j])) << j << " " << n;
    }
}

TEST(RotationBranches, SafeBasinListsHoldTheTrianglesLinkedAtTheirSafeLevel) {
  // A grid of 12 x 30 x 2 triangles, each edge's length drawn below, between and above the two
  // thresholds, a few unsafe edges: the list of a triangle with a safe level l holds exactly the
  // triangles a search reaches from it along edges of level <= l, in increasing order.
  const meshik::TriangleAdjacency adjacency = strip_adjacency(12, 30);
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  std::mt19937 random(5);
  std::uniform_int_distribution<int> pick(0, 9);
  const double lengths[] = {1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 0.05, 0.05, 0.05, 0.5};
  std::vector<double> distances(adjacency.neighbour.size());
  std::vector<int> unsafe;
  for (int j = 0; j < m; ++j)
    for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s) {
      const int n = adjacency.neighbour[s];
      if (n < j) continue;  // the lesser end draws the length; the other end copies it
      distances[s] = lengths[pick(random)];
      for (int t = adjacency.start[n]; t < adjacency.start[n + 1]; ++t)
        if (adjacency.neighbour[t] == j) distances[t] = distances[s];
      if (j % 97 == 0) unsafe.insert(unsafe.end(), {j, n});
    }
  const meshik::SafeBasins basins = meshik::safe_basins(adjacency, distances.data(), {1e-3, 1e-1}, unsafe);
  const meshik::SafeBasinMembers members = meshik::safe_basin_members(adjacency, basins);
  int at_level[3] = {0, 0, 0};  // triangles of safe level -1, 0 and 1
  int first_of_previous = -1;
  for (size_t b = 0; b + 1 < members.start.size(); ++b) {
    EXPECT_GT(members.member[members.start[b]], first_of_previous);  // numbered by least triangle
    first_of_previous = members.member[members.start[b]];
  }
  for (int j = 0; j < m; ++j) {
    const int level = basins.safe_level[j];
    ++at_level[level + 1];
    if (level < 0) {
      EXPECT_EQ(members.basin_of[j], -1) << j;
      continue;
    }
    std::vector<char> reached(m, 0);
    std::vector<int> basin = {j};
    reached[j] = 1;
    for (size_t head = 0; head < basin.size(); ++head)
      for (int s = adjacency.start[basin[head]]; s < adjacency.start[basin[head] + 1]; ++s)
        if (basins.edge_level[s] <= level && !reached[adjacency.neighbour[s]]) {
          reached[adjacency.neighbour[s]] = 1;
          basin.push_back(adjacency.neighbour[s]);
        }
    std::sort(basin.begin(), basin.end());
    const int b = members.basin_of[j];
    ASSERT_GE(b, 0) << j;
    const auto first = members.member.begin();
    EXPECT_EQ(std::vector<int>(first + members.start[b], first + members.start[b + 1]), basin) << j;
  }
  for (int count : at_level) EXPECT_GT(count, 0);
}

TEST(RotationBranches, TriangleComponentsAreNumberedByTheirLeastTriangle) {
  std::vector<int> triangles;
  int vertices = append_strip(1, 2, 0, triangles);  // triangles 0-3
  vertices += append_strip(1, 1, vertices, triangles);  // triangles 4-5
  triangles.insert(triangles.end(), {0, 1, vertices});  // shares the edge (0, 1) with triangle 0
  const meshik::TriangleAdjacency adjacency = meshik::triangle_adjacency(triangles.data(), 7, vertices + 1);
  const meshik::TriangleComponents components = meshik::triangle_components(adjacency);
  EXPECT_EQ(components.count, 2);
  EXPECT_EQ(components.component_of, std::vector<int>({0, 0, 0, 0, 1, 1, 0}));
}

// The closed-form batch against the SVD polar decomposition of each triangle's deformation
// gradient: triangles of their own (no shared vertices) deformed by a rotation (every angle of
// test_rotation_vectors) times a random symmetric positive definite stretch, by a rotation alone,
// a reflection (the triangle mirrored), a stretch of condition 1e6 along the first edge, and a
// collapse onto a line (T singular: the SVD lanes).
TEST(So3, TrianglePolarDecompositionMatchesTheSvdOne) {
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  std::vector<double> rest, deformed;
  std::vector<int> triangles;
  const auto add = [&](const Eigen::Matrix3d& map) {
    const int first = static_cast<int>(rest.size() / 3);
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Vector3d v(normal(random), normal(random), normal(random));
      const Eigen::Vector3d w = map * v + Eigen::Vector3d(normal(random), normal(random), normal(random));
      rest.insert(rest.end(), {v.x(), v.y(), v.z()});
      deformed.insert(deformed.end(), {w.x(), w.y(), w.z()});
      triangles.push_back(first + corner);
    }
  };
  for (const Eigen::Vector3d& phi : test_rotation_vectors()) {
    Eigen::Matrix3d stretch;
    for (int e = 0; e < 9; ++e) stretch(e) = 0.3 * normal(random);
    add(so3_exp(phi) * (Eigen::Matrix3d::Identity() + stretch * stretch.transpose()));
    add(so3_exp(phi));
  }
  add(Eigen::Vector3d(1, 1, -1).asDiagonal());
  add(Eigen::Vector3d(1e3, 1e-3, 1).asDiagonal());
  const int collapsed = static_cast<int>(triangles.size() / 3);
  add(Eigen::Matrix3d::Identity());
  for (int corner = 0; corner < 3; ++corner)  // onto the line through the origin along (1, 2, 3)
    for (int d = 0; d < 3; ++d) deformed[3 * (3 * collapsed + corner) + d] = (corner + 1.0) * (d + 1.0);
  const int m = static_cast<int>(triangles.size() / 3);
  const meshik::TriangleFrames frames = meshik::compute_triangle_frames(rest.data(), triangles.data(), m);
  constexpr int N = meshik::kPolarLanes;
  for (int first = 0; first < m; first += N) {
    const int count = std::min(N, m - first);
    double rotation_lanes[9][N], stretch_lanes[6][N], log_lanes[3][N];
    meshik::triangle_polar_and_log_batch(frames, frames.plane_basis.data(), triangles.data(), deformed.data(), first,
                                         count, rotation_lanes, stretch_lanes, log_lanes);
    for (int l = 0; l < count; ++l) {
      const int j = first + l;
      Eigen::Matrix3d rotation;
      Eigen::Matrix<double, 3, 2> plane_stretch;
      for (int e = 0; e < 9; ++e) rotation(e / 3, e % 3) = rotation_lanes[e][l];
      for (int e = 0; e < 6; ++e) plane_stretch(e / 2, e % 2) = stretch_lanes[e][l];
      const Eigen::Vector3d log(log_lanes[0][l], log_lanes[1][l], log_lanes[2][l]);
      const Eigen::Matrix3d t = meshik::deformation_gradient(frames, triangles.data(), deformed.data(), j);
      const Eigen::Matrix<double, 3, 2> basis = meshik::plane_basis_of(frames, j);
      const meshik::PolarDecomposition svd = polar_decomposition(t);
      const double scale = std::max(1.0, t.norm());
      EXPECT_LT((rotation - svd.rotation).norm(), 1e-12) << "triangle " << j << "\n" << t;
      EXPECT_LT((plane_stretch - (svd.stretch - Eigen::Matrix3d::Identity()) * basis).norm(), 1e-12 * scale)
          << "triangle " << j;
      EXPECT_LT((log - so3_log(svd.rotation)).norm(), 1e-12) << "triangle " << j;
      EXPECT_LT((rotation * (basis + plane_stretch) - t * basis).norm(), 1e-13 * scale) << "triangle " << j;
    }
  }
  EXPECT_EQ(collapsed, m - 1);
}

}  // namespace
