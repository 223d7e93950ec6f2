// The fast pose-aware decimator (decimate_example_set_fast, cpp_core/decimate/src/fast): a subset of
// the original vertices, locked vertices kept, the target reached, the distance bound kept in every
// pose, the same result for any thread count, non-manifold parts kept, one-line errors for bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "meshik/decimate.h"
#include "test_meshik_support.h"

namespace {

using meshik::DecimationResult;
using meshik::DistanceBound;

// A 602-vertex capped tube (1,200 triangles) with a bent, a twisted and a bulged example.
const meshik_test::ExampleMeshes& tube() {
  static const meshik_test::ExampleMeshes meshes = meshik_test::make_tube_examples(30, 20);
  return meshes;
}

const std::vector<int> kLocked = {0, 7, 310, 599, 601};

// Takes the tube and its examples' decimation; checks the kept vertices are an increasing subset of
// the original ones, the triangles index them, and every original vertex maps onto a kept one that
// maps onto itself.
void expect_vertex_subset(const DecimationResult& result, int num_vertices) {
  ASSERT_FALSE(result.kept_vertices.empty());
  EXPECT_TRUE(std::is_sorted(result.kept_vertices.begin(), result.kept_vertices.end()));
  EXPECT_EQ(std::adjacent_find(result.kept_vertices.begin(), result.kept_vertices.end()), result.kept_vertices.end());
  EXPECT_GE(result.kept_vertices.front(), 0);
  EXPECT_LT(result.kept_vertices.back(), num_vertices);
  const int kept = static_cast<int>(result.kept_vertices.size());
  for (int v : result.triangles) ASSERT_TRUE(v >= 0 && v < kept);
  ASSERT_EQ(static_cast<int>(result.vertex_map.size()), num_vertices);
  for (int v = 0; v < num_vertices; ++v) ASSERT_TRUE(result.vertex_map[v] >= 0 && result.vertex_map[v] < kept);
  for (int i = 0; i < kept; ++i) EXPECT_EQ(result.vertex_map[result.kept_vertices[i]], i);
}

TEST(DecimateFast, KeepsASubsetLockedVerticesAndReachesTheTarget) {
  const auto& m = tube();
  const DecimationResult result = meshik::decimate_example_set_fast(m.view(), m.example_pointers(), kLocked, 300);
  expect_vertex_subset(result, m.num_vertices());
  EXPECT_LE(result.triangles.size() / 3, 300u);
  EXPECT_GE(result.triangles.size() / 3, 290u);  // one collapse removes at most two triangles
  for (int v : kLocked) EXPECT_TRUE(std::binary_search(result.kept_vertices.begin(), result.kept_vertices.end(), v)) << v;
  // a closed tube stays closed: every edge in two triangles, V - E + F = 2
  std::set<std::pair<int, int>> directed;
  for (size_t t = 0; t < result.triangles.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(directed.insert({result.triangles[t + k], result.triangles[t + (k + 1) % 3]}).second);
  for (const auto& edge : directed) EXPECT_TRUE(directed.count({edge.second, edge.first}));
  const long faces = static_cast<long>(result.triangles.size() / 3);
  EXPECT_EQ(static_cast<long>(result.kept_vertices.size()) - faces * 3 / 2 + faces, 2);
}

TEST(DecimateFast, StopsAtATetrahedronRatherThanFoldIt) {
  // an octahedron asked for 1 triangle: a tetrahedron is as far as a closed surface can go
  const std::vector<double> points = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  const std::vector<int> octahedron = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  const DecimationResult result =
      meshik::decimate_example_set_fast({points.data(), 6, octahedron.data(), 8}, {}, {}, 1, 180.0);
  EXPECT_EQ(result.triangles.size(), 12u);
  EXPECT_EQ(result.kept_vertices.size(), 4u);
}

TEST(DecimateFast, SameResultForAnyThreadCount) {
  const auto& m = tube();
  const DistanceBound bound{0.01, 1.25, 20};
  const DecimationResult one = meshik::decimate_example_set_fast(m.view(), m.example_pointers(), kLocked, 200, 60.0, bound, 1);
  for (int threads : {2, 3, 0}) {
    const DecimationResult other =
        meshik::decimate_example_set_fast(m.view(), m.example_pointers(), kLocked, 200, 60.0, bound, threads);
    EXPECT_EQ(one.kept_vertices, other.kept_vertices) << threads;
    EXPECT_EQ(one.triangles, other.triangles) << threads;
    EXPECT_EQ(one.vertex_map, other.vertex_map) << threads;
    EXPECT_EQ(one.worst_distance, other.worst_distance) << threads;
    EXPECT_EQ(one.bound, other.bound) << threads;
  }
}

TEST(DecimateFast, KeepsTheDistanceBoundAndRelaxesItToReachTheTarget) {
  const auto& m = tube();
  const DecimationResult free = meshik::decimate_example_set_fast(m.view(), m.example_pointers(), kLocked, 200);
  EXPECT_TRUE(std::isinf(free.bound));
  EXPECT_GT(free.worst_distance, 0.0);
  const DistanceBound half{0.5 * free.worst_distance, 1.25, 20};
  const DecimationResult bounded = meshik::decimate_example_set_fast(m.view(), m.example_pointers(), kLocked, 200, 60.0, half);
  EXPECT_LE(bounded.triangles.size() / 3, 200u);
  EXPECT_LE(bounded.worst_distance, bounded.bound);
  EXPECT_NEAR(bounded.bound, half.max_distance * std::pow(1.25, bounded.relaxations), 1e-12 * bounded.bound);
  // a bound no collapse can keep is relaxed until the target is reached
  const DistanceBound tiny{1e-9, 2.0, 60};
  const DecimationResult relaxed = meshik::decimate_example_set_fast(m.view(), m.example_pointers(), kLocked, 200, 60.0, tiny);
  EXPECT_LE(relaxed.triangles.size() / 3, 200u);
  EXPECT_GE(relaxed.relaxations, 1);
  EXPECT_LE(relaxed.worst_distance, relaxed.bound);
}

TEST(DecimateFast, KeepsTheNonManifoldPartsAndDecimatesTheRest) {
  // two tubes touching at one vertex (whose triangles form two fans), one triangle listed twice
  const auto& m = tube();
  const int n = m.num_vertices();
  std::vector<double> points(m.rest);
  for (int i = 0; i < 3 * n; ++i) points.push_back(m.rest[i] + (i % 3 == 0 ? 3.0 : 0.0));
  std::vector<int> triangles(m.triangles);
  for (int v : m.triangles) triangles.push_back(v == 0 ? 0 : v + n);
  triangles.insert(triangles.end(), m.triangles.begin() + 15, m.triangles.begin() + 18);  // triangle 5 again
  const DecimationResult result = meshik::decimate_example_set_fast(
      {points.data(), 2 * n, triangles.data(), static_cast<int>(triangles.size() / 3)}, {}, {}, 600);
  expect_vertex_subset(result, 2 * n);
  EXPECT_LE(result.triangles.size() / 3, 600u);
  for (int v : {0, m.triangles[15], m.triangles[16], m.triangles[17]})
    EXPECT_TRUE(std::binary_search(result.kept_vertices.begin(), result.kept_vertices.end(), v)) << v;
}

// Takes a function that should throw InputError; returns its message (empty if it did not throw).
template <class Call>
std::string input_error(Call call) {
  try {
    call();
  } catch (const meshik::InputError& error) {
    return error.what();
  }
  return std::string();
}

TEST(DecimateFast, NamesWhatIsWrongWithBadInput) {
  const auto& m = tube();
  const auto run = [&](const meshik::MeshView& view, const std::vector<int>& locked, int target) {
    return [=] { meshik::decimate_example_set_fast(view, {}, locked, target); };
  };
  EXPECT_EQ(input_error(run(m.view(), {602}, 100)), "locked vertex 602 is out of range (the mesh has 602 vertices)");
  EXPECT_EQ(input_error(run(m.view(), {}, 0)), "the target triangle count must be at least 1");
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
  const std::vector<int> out_of_range = {0, 1, 5};
  EXPECT_EQ(input_error(run({points.data(), 5, out_of_range.data(), 1}, {}, 1)),
            "triangle 0 has vertex 5, out of range (the mesh has 5 vertices)");
  const std::vector<int> repeated = {0, 1, 1};
  EXPECT_EQ(input_error(run({points.data(), 5, repeated.data(), 1}, {}, 1)), "triangle 0 repeats a vertex (0, 1, 1)");
}

}  // namespace
