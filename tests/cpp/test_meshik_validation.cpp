// Every kind of bad input raises InputError with a message naming the element.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "test_meshik_support.h"

namespace {

using meshik::ExampleSet;
using meshik::InputError;
using meshik::Solver;
using meshik_test::ExampleMeshes;

// Expects call() to throw InputError whose message contains `expected`.
void expect_input_error(const std::function<void()>& call, const std::string& expected) {
  try {
    call();
    ADD_FAILURE() << "no InputError; expected \"" << expected << "\"";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(expected), std::string::npos)
        << "message: " << error.what() << "\nexpected to contain: " << expected;
  }
}

class Validation : public ::testing::Test {
 protected:
  void build() { ExampleSet(meshes_.view(), meshes_.example_pointers()); }
  ExampleMeshes meshes_ = meshik_test::make_tube_examples();
};

TEST_F(Validation, DegenerateTriangleIsNamed) {
  // Collapse triangle 7 onto a line: move its third corner onto the midpoint of the first two.
  const int* t = &meshes_.triangles[3 * 7];
  for (int d = 0; d < 3; ++d)
    meshes_.rest[3 * t[2] + d] = 0.5 * (meshes_.rest[3 * t[0] + d] + meshes_.rest[3 * t[1] + d]);
  // Other triangles around that corner may degenerate too; the first one found is named.
  int first = -1;
  for (int j = 0; j < meshes_.num_triangles() && first < 0; ++j) {
    const int* u = &meshes_.triangles[3 * j];
    const Eigen::Vector3d a = Eigen::Vector3d::Map(&meshes_.rest[3 * u[0]]);
    const Eigen::Vector3d b = Eigen::Vector3d::Map(&meshes_.rest[3 * u[1]]);
    const Eigen::Vector3d c = Eigen::Vector3d::Map(&meshes_.rest[3 * u[2]]);
    if ((b - a).cross(c - a).norm() < 1e-12) first = j;
  }
  ASSERT_GE(first, 0);
  expect_input_error([&] { build(); },
                     "triangle " + std::to_string(first) + " has zero area in the rest mesh");
}

TEST_F(Validation, OutOfRangeAndRepeatedTriangleIndicesAreNamed) {
  meshes_.triangles[3 * 12 + 1] = 9001;
  expect_input_error([&] { build(); }, "triangle 12 has vertex index 9001 out of range [0, 132)");
  meshes_.triangles[3 * 12 + 1] = -1;
  expect_input_error([&] { build(); }, "triangle 12 has vertex index -1 out of range");
  meshes_.triangles[3 * 12 + 1] = meshes_.triangles[3 * 12 + 2];
  expect_input_error([&] { build(); }, "triangle 12 repeats a vertex");
}

TEST_F(Validation, NonFiniteCoordinatesAreNamed) {
  meshes_.examples[2][3 * 17 + 1] = std::numeric_limits<double>::quiet_NaN();
  expect_input_error([&] { build(); }, "example 2 vertex 17 has a non-finite coordinate");
  meshes_.rest[3 * 5] = std::numeric_limits<double>::infinity();
  expect_input_error([&] { build(); }, "rest vertex 5 has a non-finite coordinate");
}

TEST_F(Validation, EmptyMeshAndMissingExampleAreNamed) {
  expect_input_error([&] { ExampleSet(meshik::MeshView{}, {}); }, "the rest mesh has no vertices");
  meshik::MeshView no_triangles = meshes_.view();
  no_triangles.num_triangles = 0;
  expect_input_error([&] { ExampleSet(no_triangles, {}); }, "the rest mesh has no triangles");
  expect_input_error([&] { ExampleSet(meshes_.view(), {meshes_.rest.data(), nullptr}); },
                     "example 1 is missing");
}

TEST_F(Validation, HandlesAreChecked) {
  const auto set = std::make_shared<ExampleSet>(meshes_.view(), meshes_.example_pointers());
  expect_input_error([&] { Solver(set, {}); }, "no handles");
  expect_input_error([&] { Solver(set, {3, 200}); }, "handle 1 (vertex 200) is out of range [0, 132)");
  expect_input_error([&] { Solver(set, {3, 8, 3}); }, "handle 2 (vertex 3) repeats handle 0");
  meshik::SolverOptions options;
  options.weight_regularization = -1.0;
  expect_input_error([&] { Solver(set, {3}, options); }, "weight_regularization must be");
  options = {};
  options.max_iterations = -2;
  expect_input_error([&] { Solver(set, {3}, options); }, "max_iterations must be >= 0");
}

TEST_F(Validation, ComponentWithoutHandleNamesOneOfItsVertices) {
  // A second tube, shifted, as another connected component (vertices 132 .. 263).
  const int n = meshes_.num_vertices();
  const size_t triangle_values = meshes_.triangles.size();
  for (int v = 0; v < n; ++v)
    meshes_.rest.insert(meshes_.rest.end(),
                        {meshes_.rest[3 * v] + 3.0, meshes_.rest[3 * v + 1], meshes_.rest[3 * v + 2]});
  for (size_t e = 0; e < triangle_values; ++e) meshes_.triangles.push_back(meshes_.triangles[e] + n);
  for (auto& example : meshes_.examples) example.insert(example.end(), example.begin(), example.end());
  const auto set = std::make_shared<ExampleSet>(meshes_.view(), meshes_.example_pointers());
  expect_input_error([&] { Solver(set, {0, 40}); },
                     "the connected component containing vertex 132 (132 vertices) has no handle");
  EXPECT_NO_THROW(Solver(set, {0, 140}));
}

TEST_F(Validation, TargetsAndWeightsMustBeFinite) {
  const auto set = std::make_shared<ExampleSet>(meshes_.view(), meshes_.example_pointers());
  const Solver solver(set, {3, 50});
  std::vector<double> targets = meshik_test::gather_rows(meshes_.rest, {3, 50});
  targets[4] = std::numeric_limits<double>::quiet_NaN();
  expect_input_error([&] { solver.solve(targets.data()); },
                     "target 1 (handle vertex 50) has a non-finite coordinate");
  targets[4] = 0.0;
  const double weights[3] = {0.0, std::numeric_limits<double>::infinity(), 0.0};
  expect_input_error([&] { solver.solve(targets.data(), weights); }, "initial weight 1 is not finite");
  expect_input_error([&] { set->blend(weights); }, "weight 1 is not finite");
}

}  // namespace
