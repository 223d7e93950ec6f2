// Issue 28: the paper's free blend (S(w) = sum_i w_i S_i) and spatially varying weights (one
// weight vector per region, a partition of unity over the triangles). The free blend's exact
// Jacobian and second derivatives and the per-triangle blend against finite differences; the
// reduced energy's gradient and Hessian with free weights and with regions against finite
// differences; one region reproduces today's solve bit for bit; regions from vertex groups and
// from the examples are partitions of unity; the examples are reproduced with regions.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include <Eigen/Dense>

#include "blend_regions.h"
#include "example_set_impl.h"
#include "feature_space.h"
#include "gauss_newton.h"
#include "pose_evaluation.h"
#include "rest_example.h"
#include "pose_system.h"
#include "test_meshik_support.h"

namespace {

using meshik::Blend;
using meshik::FeatureSpace;
using meshik::kLanes;
using meshik_test::ExampleMeshes;

// out block of lane l: the (#E + 1) 3 by 2 blocks (F, then dF/dw_i), row-major.
std::vector<double> lane_block(const std::vector<double>& out, int k, int l) {
  std::vector<double> block;
  for (int e = 0; e < 6 * (k + 1); ++e) block.push_back(out[e * kLanes + l]);
  return block;
}

struct Case {
  FeatureSpace space;
  Blend blend;
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return std::string(info.param.space == FeatureSpace::kNonlinear ? "Nonlinear" : "Linear") +
         (info.param.blend == Blend::kFree ? "Free" : "Affine");
}

class BlendModes : public ::testing::TestWithParam<Case> {
 protected:
  ExampleMeshes meshes_ = meshik_test::make_tube_examples();
  std::shared_ptr<meshik::ExampleSet> set_ = std::make_shared<meshik::ExampleSet>(
      meshes_.view(), meshes_.example_pointers(), meshik::ProgressCallback{}, 0, meshik::FeaturePrecision::kDouble);
  const meshik::ExampleSet::Impl& impl() const { return set_->impl(); }
};

TEST_P(BlendModes, UnitWeightsGiveTheExample) {
  const int k = 3;
  for (int i = 0; i < k; ++i) {
    std::vector<double> w(k, 0.0);
    w[i] = 1.0;
    const std::vector<double> pose = impl().to_internal(meshes_.examples[i].data());
    std::vector<double> out(meshik::blend_batch_size(k));
    for (int batch = 0; batch < impl().features.num_batches; ++batch) {
      meshik::blend_batch(impl().features, GetParam().space, w.data(), batch, out.data(), GetParam().blend);
      for (int l = 0; l < kLanes && batch * kLanes + l < impl().num_triangles; ++l) {
        const int j = batch * kLanes + l;
        double g[6];
        meshik::corner_gradients(impl().frames.gradient.data() + meshik::kGradientEntries * j, g);
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 2; ++d) {
            double q = 0.0;
            for (int corner = 0; corner < 3; ++corner)
              q += pose[3 * impl().triangles[3 * j + corner] + c] * g[2 * corner + d];
            EXPECT_NEAR(out[(2 * c + d) * kLanes + l], q, 1e-11) << "example " << i << " triangle " << j;
          }
      }
    }
  }
}

TEST_P(BlendModes, FreeBlendDiffersFromAffineAwayFromTheExamples) {
  // sum_i w_i != 1: the free stretch scales by the sum, the affine one does not.
  const std::vector<double> w = {0.3, 0.2, 0.1};
  std::vector<double> affine(meshik::blend_batch_size(3)), free(affine.size());
  meshik::blend_batch(impl().features, GetParam().space, w.data(), 0, affine.data(), Blend::kAffine);
  meshik::blend_batch(impl().features, GetParam().space, w.data(), 0, free.data(), Blend::kFree);
  double difference = 0.0;
  for (int e = 0; e < 6 * kLanes; ++e) difference += std::abs(affine[e] - free[e]);
  EXPECT_GT(difference, 0.1);
}

TEST_P(BlendModes, JacobianMatchesFiniteDifferencesWithSharedAndPerTriangleWeights) {
  const int k = 3;
  const std::vector<double> w = {0.9, 1.7, -0.4};
  // Per lane: w scaled and shifted differently for each triangle.
  std::vector<double> lanes(k * kLanes);
  for (int i = 0; i < k; ++i)
    for (int l = 0; l < kLanes; ++l) lanes[i * kLanes + l] = w[i] * (1.0 - 0.1 * l) + 0.05 * l;
  const double h = 1e-6;
  for (int batch = 0; batch < impl().features.num_batches; batch += 5) {
    std::vector<double> out(meshik::blend_batch_size(k)), plus(out.size()), minus(out.size());
    meshik::blend_batch_lanes(impl().features, GetParam().space, GetParam().blend, lanes.data(), batch, out.data());
    for (int i = 0; i < k; ++i) {
      std::vector<double> lp = lanes, lm = lanes;
      for (int l = 0; l < kLanes; ++l) lp[i * kLanes + l] += h, lm[i * kLanes + l] -= h;
      meshik::blend_batch_lanes(impl().features, GetParam().space, GetParam().blend, lp.data(), batch, plus.data());
      meshik::blend_batch_lanes(impl().features, GetParam().space, GetParam().blend, lm.data(), batch, minus.data());
      for (int e = 0; e < 6 * kLanes; ++e)
        EXPECT_NEAR(out[(i + 1) * 6 * kLanes + e], (plus[e] - minus[e]) / (2 * h), 1e-7)
            << "batch " << batch << " weight " << i << " entry " << e;
    }
    // Lane l of the per-lane blend equals the shared blend at lane l's weights.
    for (int l = 0; l < kLanes; ++l) {
      std::vector<double> shared(k), single(out.size());
      for (int i = 0; i < k; ++i) shared[i] = lanes[i * kLanes + l];
      meshik::blend_batch(impl().features, GetParam().space, shared.data(), batch, single.data(), GetParam().blend);
      const std::vector<double> a = lane_block(out, k, l), b = lane_block(single, k, l);
      for (size_t e = 0; e < a.size(); ++e) EXPECT_NEAR(a[e], b[e], 1e-12) << "lane " << l;
    }
  }
}

TEST_P(BlendModes, CurvatureMatchesFiniteDifferencesOfTheJacobian) {
  if (GetParam().space == FeatureSpace::kLinear) GTEST_SKIP() << "the linear space has no second derivatives";
  const int k = 3;
  const meshik::ExampleFeatures& features = impl().features;
  const std::vector<double> w = {0.9, 1.7, -0.4};
  constexpr int N = meshik::kCurvatureBatches * kLanes;
  std::vector<double> lanes(k * N);
  for (int i = 0; i < k; ++i)
    for (int l = 0; l < N; ++l) lanes[i * N + l] = w[i] + 0.03 * l;
  std::mt19937 random(5);
  std::normal_distribution<double> normal;
  std::vector<double> residual(6 * N);  // the two batches' 6 rows of kLanes, one after the other
  for (double& r : residual) r = normal(random);
  std::vector<float> scratch(meshik::curvature_scratch_size(k));
  const double h = 1e-6;
  for (int batch = 0; batch + 1 < features.num_batches; batch += 6) {
    const float* curvature =
        meshik::residual_curvature_lanes(features, GetParam().blend, lanes.data(), batch, residual.data(), scratch.data());
    for (int half = 0; half < 2; ++half)
      for (int b = 0; b < k; ++b) {
        std::vector<double> plus(k * kLanes), minus(k * kLanes), out_plus(meshik::blend_batch_size(k)),
            out_minus(out_plus.size());
        for (int i = 0; i < k; ++i)
          for (int l = 0; l < kLanes; ++l) {
            plus[i * kLanes + l] = minus[i * kLanes + l] = lanes[i * N + half * kLanes + l];
            if (i == b) plus[i * kLanes + l] += h, minus[i * kLanes + l] -= h;
          }
        meshik::blend_batch_lanes(features, FeatureSpace::kNonlinear, GetParam().blend, plus.data(), batch + half,
                                  out_plus.data());
        meshik::blend_batch_lanes(features, FeatureSpace::kNonlinear, GetParam().blend, minus.data(), batch + half,
                                  out_minus.data());
        for (int a = b; a < k; ++a)
          for (int l = 0; l < kLanes; ++l) {
            double expected = 0.0, scale = 0.0;
            for (int e = 0; e < 6; ++e) {
              const int index = ((a + 1) * 6 + e) * kLanes + l;
              const double term = residual[(half * 6 + e) * kLanes + l] * (out_plus[index] - out_minus[index]) / (2 * h);
              expected += term;
              scale += std::abs(term);
            }
            EXPECT_NEAR(curvature[(a * k + b) * N + half * kLanes + l], expected, 1e-5 * (1.0 + scale))
                << "batch " << batch + half << " lane " << l << " pair " << a << "," << b;
          }
      }
  }
}

INSTANTIATE_TEST_SUITE_P(SpacesAndBlends, BlendModes,
                         ::testing::Values(Case{FeatureSpace::kNonlinear, Blend::kFree},
                                           Case{FeatureSpace::kLinear, Blend::kFree},
                                           Case{FeatureSpace::kNonlinear, Blend::kAffine},
                                           Case{FeatureSpace::kLinear, Blend::kAffine}),
                         case_name);

// The tube with handles at 8 farthest points, targets between examples 0 and 1.
struct HandleProblem {
  std::vector<int> internal_handles;
  std::vector<double> targets;
};

HandleProblem tube_problem(const ExampleMeshes& meshes, const meshik::ExampleSet::Impl& set) {
  HandleProblem problem;
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 8);
  problem.targets = meshik_test::gather_rows(meshes.examples[0], handles);
  for (size_t e = 0; e < problem.targets.size(); ++e)
    problem.targets[e] += 0.3 * meshes.examples[1][3 * handles[e / 3] + e % 3];
  for (int h : handles) problem.internal_handles.push_back(set.internal_of_vertex[h]);
  return problem;
}

// Checks at weights w that g = -(1/2) d phi/dw and S + second-order term = -dg/dw (finite differences).
void expect_exact_model(meshik::PoseEvaluator& evaluator, const std::vector<double>& w) {
  const int k = static_cast<int>(w.size());
  meshik::PoseEvaluation at, plus, minus;
  evaluator.evaluate(w.data(), true, at);
  evaluator.add_second_order(at);
  const double h = 1e-5;
  for (int i = 0; i < k; ++i) {
    std::vector<double> wp = w, wm = w;
    wp[i] += h;
    wm[i] -= h;
    evaluator.evaluate(wp.data(), true, plus);
    evaluator.evaluate(wm.data(), true, minus);
    EXPECT_NEAR(at.step_rhs(i), -(plus.energy - minus.energy) / (4 * h), 1e-6 * std::abs(at.energy)) << "weight " << i;
    const Eigen::VectorXd hessian_column = -(plus.step_rhs - minus.step_rhs) / (2 * h);
    const Eigen::VectorXd model_column = (at.schur + at.second_order).col(i);
    EXPECT_LT((hessian_column - model_column).norm(), 1e-5 * model_column.norm()) << "column " << i;
  }
}

class ReducedEnergy : public ::testing::TestWithParam<FeatureSpace> {
 protected:
  ExampleMeshes meshes_ = meshik_test::make_tube_examples();
  meshik::ExampleSet set_{meshes_.view(), meshes_.example_pointers()};
  HandleProblem problem_ = tube_problem(meshes_, set_.impl());
  meshik::PoseSystem system_{set_.impl(), problem_.internal_handles};
};

TEST_P(ReducedEnergy, FreeGradientAndHessianMatchFiniteDifferences) {
  meshik::EvaluationBuffers buffers;
  meshik::PoseEvaluator evaluator(set_.impl(), system_, GetParam(), 0.5, problem_.targets.data(), buffers, 1,
                                  Blend::kFree);
  expect_exact_model(evaluator, {0.6, 0.8, -0.3});
  // With the rest pose as example 0 (the Solver's free blend), alone and with regions.
  const meshik::ExampleFeatures with_rest = meshik::with_rest_example(set_.impl().features);
  meshik::PoseEvaluator rest_first(set_.impl(), system_, GetParam(), 0.5, problem_.targets.data(), buffers, 1,
                                   Blend::kFree, nullptr, &with_rest);
  ASSERT_EQ(rest_first.num_weights(), 4);
  expect_exact_model(rest_first, {0.4, 0.6, 0.8, -0.3});
  const meshik::BlendRegions regions = meshik::regions_from_examples(set_, 2, 0.7);
  meshik::PoseEvaluator rest_regions(set_.impl(), system_, GetParam(), 0.5, problem_.targets.data(), buffers, 1,
                                     Blend::kFree, &regions, &with_rest);
  ASSERT_EQ(rest_regions.num_weights(), 8);
  expect_exact_model(rest_regions, {0.4, 0.6, 0.8, -0.3, -0.2, 0.5, 0.9, -0.1});
}

TEST_P(ReducedEnergy, RegionGradientAndHessianMatchFiniteDifferences) {
  for (Blend blend : {Blend::kAffine, Blend::kFree}) {
    const meshik::BlendRegions regions = meshik::regions_from_examples(set_, 3, 0.7);
    ASSERT_EQ(regions.num_regions, 3);
    meshik::EvaluationBuffers buffers;
    meshik::PoseEvaluator evaluator(set_.impl(), system_, GetParam(), 0.5, problem_.targets.data(), buffers, 1, blend,
                                    &regions);
    ASSERT_EQ(evaluator.num_weights(), 9);
    expect_exact_model(evaluator, {0.6, 0.8, -0.3, 0.5, 0.9, -0.1, 0.7, 0.6, -0.4});
  }
}

INSTANTIATE_TEST_SUITE_P(BothFeatureSpaces, ReducedEnergy,
                         ::testing::Values(FeatureSpace::kNonlinear, FeatureSpace::kLinear),
                         [](const auto& info) { return info.param == FeatureSpace::kNonlinear ? "Nonlinear" : "Linear"; });

TEST(BlendRegions, OneRegionReproducesTodaysSolveBitForBit) {
  const ExampleMeshes meshes = meshik_test::make_tube_examples();
  const meshik::ExampleSet set(meshes.view(), meshes.example_pointers());
  const HandleProblem problem = tube_problem(meshes, set.impl());
  const meshik::PoseSystem system(set.impl(), problem.internal_handles);
  const meshik::BlendRegions one = meshik::regions_from_examples(set, 1, 1.0);
  ASSERT_EQ(one.num_regions, 1);
  for (Blend blend : {Blend::kAffine, Blend::kFree})
    for (int threads : {1, 2}) {
      meshik::SolverOptions options;
      options.blend = blend;
      const std::vector<double> start = {0.5, 0.5, 0.1};
      meshik::EvaluationBuffers today_buffers, region_buffers;
      meshik::PoseEvaluator today(set.impl(), system, FeatureSpace::kNonlinear, 0.0, problem.targets.data(),
                                  today_buffers, threads, blend);
      meshik::PoseEvaluator region(set.impl(), system, FeatureSpace::kNonlinear, 0.0, problem.targets.data(),
                                   region_buffers, threads, blend, &one);
      const meshik::SolveResult a = meshik::gauss_newton(today, 3, set.num_triangles(), start.data(), options, {});
      const meshik::SolveResult b = meshik::gauss_newton(region, 3, set.num_triangles(), start.data(), options, {});
      ASSERT_GT(a.iterations, 1);
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_EQ(a.vertices, b.vertices);  // exact equality of every double
      EXPECT_EQ(a.weights, b.weights);
      EXPECT_EQ(a.energies, b.energies);
    }
}

// Rows of shares sum to one, are non-negative, and the smoothness matrix is symmetric with rows
// summing to zero (a graph Laplacian: equal weights in every region cost nothing).
void expect_partition_of_unity(const meshik::BlendRegions& regions) {
  const int count = regions.num_regions;
  for (int j = 0; j < regions.num_triangles; ++j) {
    double sum = 0.0;
    for (int r = 0; r < count; ++r) {
      EXPECT_GE(regions.share[j * count + r], 0.0);
      sum += regions.share[j * count + r];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "triangle " << j;
  }
  EXPECT_LT((regions.smoothness - regions.smoothness.transpose()).norm(), 1e-12);
  EXPECT_LT(regions.smoothness.rowwise().sum().norm(), 1e-9 * (1.0 + regions.smoothness.norm()));
}

TEST(BlendRegions, VertexGroupsAndClustersArePartitionsOfUnityWithSoftBorders) {
  const ExampleMeshes meshes = meshik_test::make_tube_examples();
  const meshik::ExampleSet set(meshes.view(), meshes.example_pointers());
  // Groups by height: bottom third 0, top third 1, the middle in no group (a third region).
  std::vector<int> groups(meshes.num_vertices());
  for (int v = 0; v < meshes.num_vertices(); ++v) {
    const double z = meshes.rest[3 * v + 2];
    groups[v] = z < 1.3 ? 0 : (z > 2.7 ? 1 : -1);
  }
  const meshik::BlendRegions by_groups = meshik::regions_from_vertex_groups(set.impl(), groups, 1.0);
  EXPECT_EQ(by_groups.num_regions, 3);
  expect_partition_of_unity(by_groups);
  int soft = 0;
  for (double a : by_groups.share) soft += a > 0.0 && a < 1.0;
  EXPECT_GT(soft, 0);  // borders are blended
  EXPECT_GT(by_groups.smoothness.norm(), 0.0);
  for (int count : {2, 4, meshik::kAutomaticRegions}) {
    const meshik::BlendRegions clustered = meshik::regions_from_examples(set, count, 1.0);
    if (count > 0) EXPECT_EQ(clustered.num_regions, count);
    EXPECT_GE(clustered.num_regions, 2);
    expect_partition_of_unity(clustered);
  }
  std::vector<int> bad = groups;
  bad[5] = -3;
  EXPECT_THROW(meshik::regions_from_vertex_groups(set.impl(), bad, 1.0), meshik::InputError);
}

TEST(BlendRegions, SolverWithRegionsReproducesEachExampleFromItsOwnHandles) {
  const ExampleMeshes meshes = meshik_test::make_tube_examples();
  auto set = std::make_shared<const meshik::ExampleSet>(meshes.view(), meshes.example_pointers());
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 10);
  for (Blend blend : {Blend::kAffine, Blend::kFree}) {
    meshik::SolverOptions options;
    options.blend = blend;
    options.regions = 3;
    const meshik::Solver solver(set, handles, options);
    const int per_region = blend == Blend::kFree ? 4 : 3;  // the free blend's rest pose first
    EXPECT_EQ(solver.num_regions(), 3);
    EXPECT_EQ(solver.num_weights(), 3 * per_region);
    for (int i = 0; i < 3; ++i) {
      const std::vector<double> targets = meshik_test::gather_rows(meshes.examples[i], handles);
      const meshik::SolveResult result = solver.solve(targets.data());
      ASSERT_EQ(result.weights.size(), static_cast<size_t>(3 * per_region));
      double worst = 0.0;
      for (size_t e = 0; e < result.vertices.size(); ++e)
        worst = std::max(worst, std::abs(result.vertices[e] - meshes.examples[i][e]));
      EXPECT_LT(worst, 1e-5) << "example " << i;
    }
  }
  // The same bits for any thread count, with regions as without.
  meshik::SolverOptions one_thread, two_threads;
  one_thread.regions = two_threads.regions = 3;
  one_thread.blend = two_threads.blend = Blend::kFree;
  one_thread.threads = 1;
  two_threads.threads = 2;
  std::vector<double> targets = meshik_test::gather_rows(meshes.examples[0], handles);
  for (size_t e = 0; e < targets.size(); ++e) targets[e] = 0.5 * (targets[e] + meshes.examples[1][3 * handles[e / 3] + e % 3]);
  const meshik::SolveResult serial = meshik::Solver(set, handles, one_thread).solve(targets.data());
  const meshik::SolveResult threaded = meshik::Solver(set, handles, two_threads).solve(targets.data());
  EXPECT_EQ(serial.vertices, threaded.vertices);
  EXPECT_EQ(serial.weights, threaded.weights);
  meshik::SolverOptions bad;
  bad.regions = 0;
  EXPECT_THROW(meshik::Solver(set, handles, bad), meshik::InputError);
}

}  // namespace
