// The solver on a generated example set (a tube that bends, twists and bulges): rest handles give
// the rest pose, example handles give the example and its weight vector, Gauss-Newton lowers the
// energy every iteration, warm starts, cancellation, isolated vertices, regularization, and the
// triangles a handle dragged out of reach turns over.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "example_set_impl.h"
#include "sparse/analysis.h"
#include "sparse/subtree_schedule.h"
#include "test_meshik_support.h"

namespace {

using meshik::ExampleSet;
using meshik::FeatureSpace;
using meshik::SolveResult;
using meshik::Solver;
using meshik::SolverOptions;
using meshik_test::ExampleMeshes;

class TubeSolver : public ::testing::TestWithParam<FeatureSpace> {
 protected:
  void SetUp() override {
    meshik_test::TubeProblem problem = meshik_test::make_tube_problem();
    meshes_ = std::move(problem.meshes);
    set_ = std::move(problem.set);
    handles_ = std::move(problem.handles);
    diagonal_ = problem.diagonal;
  }
  Solver make_solver(const SolverOptions& extra = {}) const {
    SolverOptions options = extra;
    options.feature_space = GetParam();
    return Solver(set_, handles_, options);
  }
  std::vector<double> targets_from(const std::vector<double>& pose) const {
    return meshik_test::gather_rows(pose, handles_);
  }
  ExampleMeshes meshes_;
  std::shared_ptr<ExampleSet> set_;
  std::vector<int> handles_;
  double diagonal_ = 0.0;
};

TEST_P(TubeSolver, RestHandlesGiveTheRestPose) {
  const Solver solver = make_solver();
  const SolveResult result = solver.solve(targets_from(meshes_.rest).data());
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_LT(meshik_test::max_vertex_distance(result.vertices, meshes_.rest), 1e-10 * diagonal_);
  for (double w : result.weights) EXPECT_NEAR(w, 0.0, 1e-12);
  EXPECT_TRUE(result.inverted_triangles.empty());
}

TEST_P(TubeSolver, ExampleHandlesReproduceTheExampleAndItsWeights) {
  const Solver solver = make_solver();
  for (size_t i = 0; i < meshes_.examples.size(); ++i) {
    const SolveResult result = solver.solve(targets_from(meshes_.examples[i]).data());
    EXPECT_TRUE(result.converged) << "example " << i;
    EXPECT_LT(meshik_test::max_vertex_distance(result.vertices, meshes_.examples[i]),
              1e-6 * diagonal_)
        << "example " << i;
    for (size_t e = 0; e < result.weights.size(); ++e)
      EXPECT_NEAR(result.weights[e], e == i ? 1.0 : 0.0, 1e-6) << "example " << i;
    EXPECT_LT(result.residual, 1e-12);
    EXPECT_TRUE(result.inverted_triangles.empty()) << "example " << i;
  }
}

TEST_P(TubeSolver, AHandleDraggedPastItsNeighboursTurnsItsTrianglesOver) {
  // Handle 0 (vertex 0, on the tube's first ring) moved along the axis by three ring spacings,
  // the other handles left at rest: the examples cannot follow, so its triangles fold over.
  const Solver solver = make_solver();
  std::vector<double> targets = targets_from(meshes_.rest);
  ASSERT_EQ(handles_[0], 0);
  targets[2] += 1.0;
  const SolveResult result = solver.solve(targets.data());
  const std::vector<int>& inverted = result.inverted_triangles;
  ASSERT_FALSE(inverted.empty());
  EXPECT_TRUE(std::is_sorted(inverted.begin(), inverted.end()));
  bool touches_the_handle = false;
  for (int j : inverted) {
    ASSERT_GE(j, 0);
    ASSERT_LT(j, meshes_.num_triangles());
    for (int q = 0; q < 3; ++q) touches_the_handle |= meshes_.triangles[3 * j + q] == 0;
  }
  EXPECT_TRUE(touches_the_handle);
  // Each listed triangle's posed normal points away from its rest normal here (w stays near 0).
  for (int j : inverted) {
    const int* t = &meshes_.triangles[3 * j];
    auto normal = [t](const std::vector<double>& x) {
      const Eigen::Vector3d a(&x[3 * t[0]]), b(&x[3 * t[1]]), c(&x[3 * t[2]]);
      return Eigen::Vector3d((b - a).cross(c - a));
    };
    EXPECT_LT(normal(result.vertices).dot(normal(meshes_.rest)), 0.0) << "triangle " << j;
  }
}

// Targets that no blend reproduces exactly: the bend, a twist and a stretch of the handles.
std::vector<double> unreachable_targets(const ExampleMeshes& meshes, const std::vector<int>& handles) {
  std::vector<double> targets = meshik_test::gather_rows(meshes.examples[0], handles);
  for (size_t h = 0; h < handles.size(); ++h) {
    const double* twist = &meshes.examples[1][3 * handles[h]];
    targets[3 * h] += 0.7 * twist[0] + 0.2;
    targets[3 * h + 1] += 0.3 * twist[1];
    targets[3 * h + 2] *= 1.1;
  }
  return targets;
}

const std::vector<double> kRestWeights(3, 0.0);

TEST_P(TubeSolver, EveryIterationLowersTheEnergyAndTheResidualIsTheLastEnergy) {
  const Solver solver = make_solver();
  const SolveResult result = solver.solve(unreachable_targets(meshes_, handles_).data(), kRestWeights.data());
  ASSERT_GE(result.energies.size(), 2u);
  for (size_t it = 1; it < result.energies.size(); ++it)
    EXPECT_LE(result.energies[it], result.energies[it - 1]) << "iteration " << it;
  EXPECT_LT(result.energies.back(), result.energies.front());
  EXPECT_EQ(result.residual, result.energies.back());
  EXPECT_TRUE(result.converged);
  EXPECT_GT(result.residual, 1e-6);  // the targets are indeed out of reach
}

TEST_P(TubeSolver, WarmStartFromTheSolutionStopsAtOnceWithTheSamePose) {
  const Solver solver = make_solver();
  const std::vector<double> targets = unreachable_targets(meshes_, handles_);
  const SolveResult cold = solver.solve(targets.data(), kRestWeights.data());
  const SolveResult warm = solver.solve(targets.data(), cold.weights.data());
  EXPECT_LE(warm.iterations, 1);
  EXPECT_LT(warm.iterations, cold.iterations);
  EXPECT_LT(meshik_test::max_vertex_distance(warm.vertices, cold.vertices), 1e-6 * diagonal_);
  EXPECT_LE(warm.residual, cold.residual * (1.0 + 1e-9));
}

TEST_P(TubeSolver, AnyThreadCountGivesTheSameBits) {
  // A tube of 9,600 triangles: the solve's passes run over 32 chunks, sharing rows at their seams;
  // its factorization and its solves over several subtrees of the elimination tree.
  const ExampleMeshes meshes = meshik_test::make_tube_examples(121, 40);
  const auto set = std::make_shared<ExampleSet>(meshes.view(), meshes.example_pointers());
  const auto analysis = meshik::sparse::analyze_pattern(set->impl().system_analysis.analyzed_pattern());
  ASSERT_GE(meshik::sparse::subtree_schedule(analysis.symbolic, 2).root.size(), 2u);
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 8);
  const std::vector<double> targets = unreachable_targets(meshes, handles);
  std::vector<SolveResult> results;  // from the linear space's optimum, then from the rest pose
  for (int threads : {1, 2, 3, 0}) {
    SolverOptions options;
    options.feature_space = GetParam();
    options.threads = threads;
    const Solver solver(set, handles, options);
    results.push_back(solver.solve(targets.data()));
    results.push_back(solver.solve(targets.data(), kRestWeights.data()));
  }
  ASSERT_GE(results[1].iterations, 1);
  for (size_t i = 2; i < results.size(); ++i) {
    const SolveResult& serial = results[i % 2];
    EXPECT_EQ(results[i].vertices, serial.vertices) << "run " << i;
    EXPECT_EQ(results[i].weights, serial.weights) << "run " << i;
    EXPECT_EQ(results[i].energies, serial.energies) << "run " << i;
    EXPECT_EQ(results[i].inverted_triangles, serial.inverted_triangles) << "run " << i;
  }
}

TEST_P(TubeSolver, MovingHandlesReusesTheFactorAndMeetsEveryTarget) {
  const Solver solver = make_solver();
  for (const std::vector<double>* pose : {&meshes_.examples[0], &meshes_.rest, &meshes_.examples[2]}) {
    const std::vector<double> targets = targets_from(*pose);
    const SolveResult result = solver.solve(targets.data());
    EXPECT_EQ(meshik_test::gather_rows(result.vertices, handles_), targets);
    EXPECT_LT(meshik_test::max_vertex_distance(result.vertices, *pose), 1e-6 * diagonal_);
  }
}

TEST_P(TubeSolver, ZeroIterationsReturnsThePoseOfTheInitialWeights) {
  SolverOptions options;
  options.max_iterations = 0;
  const Solver solver = make_solver(options);
  const double example_one[3] = {0.0, 1.0, 0.0};
  const SolveResult result =
      solver.solve(targets_from(meshes_.examples[1]).data(), example_one);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_LT(meshik_test::max_vertex_distance(result.vertices, meshes_.examples[1]), 1e-6 * diagonal_);
}

TEST_P(TubeSolver, RegularizationPullsTheWeightsTowardsTheRestPose) {
  SolverOptions options;
  options.weight_regularization = 50.0;
  const Solver regularized = make_solver(options);
  const Solver free = make_solver();
  const std::vector<double> targets = targets_from(meshes_.examples[0]);
  const SolveResult a = regularized.solve(targets.data());
  const SolveResult b = free.solve(targets.data());
  EXPECT_LT(a.weights[0], b.weights[0] - 0.01);
  EXPECT_GT(a.weights[0], 0.0);
  double penalty = 0.0;
  for (double w : a.weights) penalty += options.weight_regularization * w * w;
  EXPECT_GE(a.residual, penalty);  // the energy includes kappa |w|^2
}

TEST_P(TubeSolver, ProgressReportsIterationsAndCancels) {
  const Solver solver = make_solver();
  const std::vector<double> targets = unreachable_targets(meshes_, handles_);
  std::vector<double> fractions;
  solver.solve(targets.data(), kRestWeights.data(), [&](double fraction, const std::string& stage) {
    EXPECT_NE(stage.find("Gauss-Newton"), std::string::npos);
    fractions.push_back(fraction);
    return true;
  });
  ASSERT_FALSE(fractions.empty());
  for (size_t i = 1; i < fractions.size(); ++i) EXPECT_GT(fractions[i], fractions[i - 1]);
  EXPECT_THROW(solver.solve(targets.data(), kRestWeights.data(), [](double, const std::string&) { return false; }),
               meshik::Cancelled);
}

TEST_P(TubeSolver, BlendAtZeroIsTheRestAndAtAUnitVectorIsThatExample) {
  // The examples to 1e-9 of the diagonal with the features stored in double, to 1e-6 (issue 13's
  // bound for single precision) with floats; the rest exactly in both (its plane bases are double).
  for (meshik::FeaturePrecision precision : {meshik::FeaturePrecision::kDouble, meshik::FeaturePrecision::kSingle}) {
    const ExampleSet set(meshes_.view(), meshes_.example_pointers(), {}, 0, precision);
    const std::vector<double> zero(3, 0.0);
    EXPECT_LT(meshik_test::max_vertex_distance(set.blend(zero.data(), GetParam()), meshes_.rest), 1e-9 * diagonal_);
    const double tolerance = (precision == meshik::FeaturePrecision::kDouble ? 1e-9 : 1e-6) * diagonal_;
    for (size_t i = 0; i < meshes_.examples.size(); ++i) {
      std::vector<double> unit(3, 0.0);
      unit[i] = 1.0;
      EXPECT_LT(meshik_test::max_vertex_distance(set.blend(unit.data(), GetParam()), meshes_.examples[i]), tolerance)
          << "example " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothFeatureSpaces, TubeSolver,
                         ::testing::Values(FeatureSpace::kNonlinear, FeatureSpace::kLinear),
                         [](const auto& info) {
                           return info.param == FeatureSpace::kNonlinear ? "Nonlinear" : "Linear";
                         });

TEST(Solver, WithoutInitialWeightsItStartsFromTheLinearSpacesOptimum) {
  const ExampleMeshes meshes = meshik_test::make_tube_examples();
  const auto set = std::make_shared<ExampleSet>(meshes.view(), meshes.example_pointers());
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 8);
  SolverOptions options;
  options.feature_space = FeatureSpace::kLinear;
  options.weight_regularization = 0.3;
  const Solver linear(set, handles, options);
  const std::vector<double> targets = unreachable_targets(meshes, handles);
  const SolveResult from_rest = linear.solve(targets.data(), kRestWeights.data());
  const SolveResult started = linear.solve(targets.data());
  EXPECT_EQ(started.iterations, 0);  // the start is the linear space's solution already
  EXPECT_TRUE(started.converged);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(started.weights[i], from_rest.weights[i], 1e-9);
  EXPECT_NEAR(started.residual, from_rest.residual, 1e-9 * from_rest.residual);
}

TEST(Solver, VerticesUsedByNoTriangleKeepTheirRestPosition) {
  ExampleMeshes meshes = meshik_test::make_tube_examples();
  const ExampleMeshes tube = meshes;
  const std::vector<int> handles = meshik_test::farthest_point_handles(tube.rest, 6);
  const std::vector<double> loose = {9.0, 8.0, 7.0};
  meshes.rest.insert(meshes.rest.end(), loose.begin(), loose.end());
  for (auto& e : meshes.examples) e.insert(e.end(), {1.0, 2.0, 3.0});
  const auto set = std::make_shared<ExampleSet>(meshes.view(), meshes.example_pointers());
  const Solver solver(set, handles);
  const SolveResult result =
      solver.solve(meshik_test::gather_rows(meshes.examples[0], handles).data());
  ASSERT_EQ(result.vertices.size(), meshes.rest.size());
  EXPECT_EQ(std::vector<double>(result.vertices.end() - 3, result.vertices.end()), loose);
  const std::vector<double> on_tube(result.vertices.begin(), result.vertices.end() - 3);
  // To issue 13's bound for features stored in single precision.
  EXPECT_LT(meshik_test::max_vertex_distance(on_tube, tube.examples[0]), 1e-6 * meshik_test::bounding_box_diagonal(tube.rest));
  const std::vector<double> zero(3, 0.0);
  const std::vector<double> blended = set->blend(zero.data());
  EXPECT_EQ(std::vector<double>(blended.end() - 3, blended.end()), loose);
}

TEST(Solver, WithoutExamplesTheRestShapeIsKept) {
  const ExampleMeshes meshes = meshik_test::make_tube_examples();
  const auto set = std::make_shared<ExampleSet>(meshes.view(), std::vector<const double*>{});
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 5);
  const Solver solver(set, handles);
  const SolveResult result = solver.solve(meshik_test::gather_rows(meshes.rest, handles).data());
  EXPECT_TRUE(result.weights.empty());
  EXPECT_LT(meshik_test::max_vertex_distance(result.vertices, meshes.rest), 1e-10);
}

}  // namespace
