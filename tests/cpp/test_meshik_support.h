// Shared helpers of the solver's tests: a generated example set (a capped tube that bends, twists
// and bulges, like the paper's "Bar"), the real example sets of ../shared/data, and pose metrics.
#pragma once

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "../../bench/obj_reader.h"
#include "../../bench/paper_handles.h"
#include "example_set_impl.h"
#include "feature_space.h"
#include "meshik/meshik.h"

namespace meshik_test {

using meshik_bench::farthest_point_handles;
using meshik_bench::gather_rows;

// A rest mesh with example poses of the same connectivity.
struct ExampleMeshes {
  std::vector<double> rest;                   // #V by 3
  std::vector<int> triangles;                 // #F by 3
  std::vector<std::vector<double>> examples;  // #E arrays of #V by 3

  int num_vertices() const { return static_cast<int>(rest.size() / 3); }
  int num_triangles() const { return static_cast<int>(triangles.size() / 3); }
  meshik::MeshView view() const {
    return {rest.data(), num_vertices(), triangles.data(), num_triangles()};
  }
  std::vector<const double*> example_pointers() const {
    std::vector<const double*> pointers;
    for (const auto& e : examples) pointers.push_back(e.data());
    return pointers;
  }
};

// A capped tube along z (length 4, radius 0.5) with `rings` rings of `segments` vertices and one
// cap centre at each end (by default 132 vertices and 260 triangles, the size of the paper's
// "Bar"). Examples: 0 bends it by 90 degrees in the y-z plane, 1 twists it by
// twist_angle about its axis, 2 bulges its middle by 30 %.
inline ExampleMeshes make_tube_examples(int rings = 13, int segments = 10,
                                        double twist_angle = 2.0) {
  const double length = 4.0, radius = 0.5, pi = 3.14159265358979323846;
  ExampleMeshes m;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * pi * s / segments;
      m.rest.insert(m.rest.end(),
                    {radius * std::cos(a), radius * std::sin(a), length * r / (rings - 1)});
    }
  const int bottom = rings * segments, top = bottom + 1;
  m.rest.insert(m.rest.end(), {0.0, 0.0, 0.0, 0.0, 0.0, length});
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      m.triangles.insert(m.triangles.end(), {a, b, d, a, d, c});
    }
  for (int s = 0; s < segments; ++s) {
    const int next = (s + 1) % segments, last = (rings - 1) * segments;
    m.triangles.insert(m.triangles.end(), {bottom, next, s, top, last + s, last + next});
  }
  const int n = m.num_vertices();
  std::vector<double> bend(m.rest), twist(m.rest), bulge(m.rest);
  const double bend_radius = length / (pi / 2.0);
  for (int v = 0; v < n; ++v) {
    const double x = m.rest[3 * v], y = m.rest[3 * v + 1], z = m.rest[3 * v + 2];
    const double t = z / length;
    const double angle = (pi / 2.0) * t;
    bend[3 * v + 1] = bend_radius - (bend_radius - y) * std::cos(angle);
    bend[3 * v + 2] = (bend_radius - y) * std::sin(angle);
    const double turn = twist_angle * t;
    twist[3 * v] = x * std::cos(turn) - y * std::sin(turn);
    twist[3 * v + 1] = x * std::sin(turn) + y * std::cos(turn);
    const double scale = 1.0 + 0.3 * std::sin(pi * t);
    bulge[3 * v] = x * scale;
    bulge[3 * v + 1] = y * scale;
  }
  m.examples = {bend, twist, bulge};
  return m;
}

// The real example sets' folder: $MESHIK_SHARED_DATA, else ../shared/data beside the
// repository; empty when absent.
inline std::string shared_data_dir() {
  const char* env = std::getenv("MESHIK_SHARED_DATA");
  const std::string dir = env ? env : "../shared/data";
  return std::filesystem::is_directory(dir) ? dir : std::string();
}

// Loads folder/rest_name as the rest mesh and folder/<name> for each example name.
inline ExampleMeshes load_example_folder(const std::string& folder, const std::string& rest_name,
                                         const std::vector<std::string>& example_names) {
  meshik_bench::TriangleMesh rest = meshik_bench::read_obj(folder + "/" + rest_name);
  ExampleMeshes m;
  m.rest = std::move(rest.vertices);
  m.triangles = std::move(rest.triangles);
  for (const std::string& name : example_names)
    m.examples.push_back(meshik_bench::read_obj(folder + "/" + name).vertices);
  return m;
}

// In a GoogleTest body: loads shared/data/<folder> (rest file `rest`, example files the braced list
// of names) as `meshes`, with `data_dir` the data folder, or skips the test when the data is absent.
#define LOAD_OR_SKIP(meshes, folder, rest, ...)                                              \
  const std::string data_dir = meshik_test::shared_data_dir();                               \
  if (data_dir.empty())                                                                      \
    GTEST_SKIP() << "real example sets not found at ../shared/data (set MESHIK_SHARED_DATA)"; \
  const meshik_test::ExampleMeshes meshes =                                                  \
      meshik_test::load_example_folder(data_dir + "/" + folder, rest, __VA_ARGS__)

// Length of the diagonal of the axis-aligned bounding box of #V by 3 positions.
inline double bounding_box_diagonal(const std::vector<double>& vertices) {
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> p(
      vertices.data(), vertices.size() / 3, 3);
  return (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
}

// Largest distance between corresponding rows of two #V by 3 arrays.
inline double max_vertex_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double largest = 0.0;
  for (size_t v = 0; v < a.size() / 3; ++v)
    largest = std::max(largest, std::hypot(a[3 * v] - b[3 * v], a[3 * v + 1] - b[3 * v + 1],
                                           a[3 * v + 2] - b[3 * v + 2]));
  return largest;
}

// Root mean square distance between corresponding rows of two #V by 3 arrays.
inline double rms_vertex_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (size_t e = 0; e < a.size(); ++e) sum += (a[e] - b[e]) * (a[e] - b[e]);
  return std::sqrt(sum / (a.size() / 3));
}

// Unit normals of the #F triangles (#F by 3 indices) of positions (#V by 3).
inline std::vector<Eigen::Vector3d> triangle_normals(const std::vector<double>& vertices,
                                                     const std::vector<int>& triangles) {
  std::vector<Eigen::Vector3d> normals;
  for (size_t j = 0; j < triangles.size() / 3; ++j) {
    const Eigen::Vector3d a = Eigen::Vector3d::Map(&vertices[3 * triangles[3 * j]]);
    const Eigen::Vector3d b = Eigen::Vector3d::Map(&vertices[3 * triangles[3 * j + 1]]);
    const Eigen::Vector3d c = Eigen::Vector3d::Map(&vertices[3 * triangles[3 * j + 2]]);
    normals.push_back((b - a).cross(c - a).normalized());
  }
  return normals;
}

// How many triangles' normals point against the reference's (dot product < 0).
inline int count_flipped_triangles(const std::vector<double>& vertices,
                                   const std::vector<double>& reference,
                                   const std::vector<int>& triangles) {
  const std::vector<Eigen::Vector3d> a = triangle_normals(vertices, triangles);
  const std::vector<Eigen::Vector3d> b = triangle_normals(reference, triangles);
  int flipped = 0;
  for (size_t j = 0; j < a.size(); ++j) flipped += a[j].dot(b[j]) < 0.0;
  return flipped;
}

// Replaces the features of `set` (built from `examples`, #E arrays of #V by 3 in the user's
// vertex order) by ones that keep the principal rotation logs: the blend without the choice of
// consistent branches, for comparison.
inline void use_principal_logs(meshik::ExampleSet& set, const std::vector<const double*>& examples) {
  auto& impl = const_cast<meshik::ExampleSet::Impl&>(set.impl());
  std::vector<std::vector<double>> internal;
  std::vector<const double*> pointers;
  for (const double* e : examples) {
    internal.push_back(impl.to_internal(e));
    pointers.push_back(internal.back().data());
  }
  const meshik::TriangleAdjacency adjacency =
      meshik::triangle_adjacency(impl.triangles.data(), impl.num_triangles, impl.num_vertices);
  // The set keeps only its frames' gradients: the features need the whole frames again.
  meshik::TriangleFrames frames =
      meshik::compute_triangle_frames(impl.rest.data(), impl.triangles.data(), impl.num_triangles);
  impl.features = meshik::compute_example_features(frames, adjacency, impl.triangles.data(), pointers, {}, false);
}

// The tube of make_tube_examples as a shared example set, with `num_handles` farthest-point
// handles and its bounding-box diagonal: the fixture of the solver's tests.
struct TubeProblem {
  ExampleMeshes meshes;
  std::shared_ptr<meshik::ExampleSet> set;
  std::vector<int> handles;
  double diagonal = 0.0;
};
inline TubeProblem make_tube_problem(int num_handles = 8) {
  TubeProblem problem;
  problem.meshes = make_tube_examples();
  problem.set = std::make_shared<meshik::ExampleSet>(problem.meshes.view(), problem.meshes.example_pointers());
  problem.handles = farthest_point_handles(problem.meshes.rest, num_handles);
  problem.diagonal = bounding_box_diagonal(problem.meshes.rest);
  return problem;
}

}  // namespace meshik_test
