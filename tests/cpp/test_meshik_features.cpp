// The feature spaces: w = 0 gives the rest pose and w = e_i example i; the exact Jacobian and
// second derivatives of the nonlinear blend against finite differences; the reduced energy's
// gradient and Hessian (Gauss-Newton matrix plus second-order term) against finite differences;
// consistent rotation-log branches on a tube twisted beyond a half turn.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include <Eigen/Dense>

#include "example_set_impl.h"
#include "feature_space.h"
#include "pose_evaluation.h"
#include "pose_system.h"
#include "test_meshik_support.h"

namespace {

using meshik::FeatureSpace;
using meshik::kLanes;
using meshik_test::ExampleMeshes;

// The (#E + 1) 3 by 2 blocks of triangle j (F_j(w), then dF_j/dw_i), row-major.
std::vector<double> blend_of(const meshik::ExampleFeatures& features, FeatureSpace space,
                             const std::vector<double>& w, int j) {
  std::vector<double> out(meshik::blend_batch_size(features.num_examples));
  meshik::blend_batch(features, space, w.data(), j / kLanes, out.data());
  std::vector<double> block;
  for (int e = 0; e < 6 * (features.num_examples + 1); ++e) block.push_back(out[e * kLanes + j % kLanes]);
  return block;
}

// The in-plane gradient Q_j(x) (3 by 2 row-major) of positions x (internal order).
std::vector<double> in_plane_gradient(const meshik::ExampleSet::Impl& set, const double* x, int j) {
  std::vector<double> q(6, 0.0);
  double g[6];
  meshik::corner_gradients(set.frames.gradient.data() + meshik::kGradientEntries * j, g);
  for (int c = 0; c < 3; ++c)
    for (int corner = 0; corner < 3; ++corner)
      for (int d = 0; d < 2; ++d) q[2 * c + d] += x[3 * set.triangles[3 * j + corner] + c] * g[2 * corner + d];
  return q;
}

class Features : public ::testing::TestWithParam<FeatureSpace> {
 protected:
  ExampleMeshes meshes_ = meshik_test::make_tube_examples();
  std::shared_ptr<meshik::ExampleSet> set_ =
      std::make_shared<meshik::ExampleSet>(meshes_.view(), meshes_.example_pointers());
  const meshik::ExampleSet::Impl& impl() const { return set_->impl(); }
};

TEST_P(Features, ZeroWeightsGiveTheRestAndUnitWeightsGiveTheExample) {
  // Exactly (to 1e-12) with the features stored in double; with floats, to their rounding.
  const int k = 3;
  for (meshik::FeaturePrecision precision : {meshik::FeaturePrecision::kDouble, meshik::FeaturePrecision::kSingle}) {
    const meshik::ExampleSet set(meshes_.view(), meshes_.example_pointers(), {}, 0, precision);
    const double tolerance = precision == meshik::FeaturePrecision::kDouble ? 1e-12 : 1e-6;
    for (int i = -1; i < k; ++i) {
      std::vector<double> w(k, 0.0);
      if (i >= 0) w[i] = 1.0;
      const std::vector<double> pose =
          set.impl().to_internal(i < 0 ? meshes_.rest.data() : meshes_.examples[i].data());
      for (int j = 0; j < meshes_.num_triangles(); ++j) {
        const std::vector<double> f = blend_of(set.impl().features, GetParam(), w, j);
        const std::vector<double> q = in_plane_gradient(set.impl(), pose.data(), j);
        for (int e = 0; e < 6; ++e)
          EXPECT_NEAR(f[e], q[e], i < 0 ? 1e-12 : tolerance) << "example " << i << " triangle " << j;
      }
    }
  }
}

TEST_P(Features, JacobianMatchesFiniteDifferences) {
  // Weights large enough that the blended rotations pass a half turn.
  const std::vector<double> w = {0.9, 1.7, -0.4};
  const double h = 1e-6;
  for (int j = 0; j < meshes_.num_triangles(); j += 7) {
    const std::vector<double> f = blend_of(impl().features, GetParam(), w, j);
    for (int i = 0; i < 3; ++i) {
      std::vector<double> plus = w, minus = w;
      plus[i] += h;
      minus[i] -= h;
      const std::vector<double> fp = blend_of(impl().features, GetParam(), plus, j);
      const std::vector<double> fm = blend_of(impl().features, GetParam(), minus, j);
      for (int e = 0; e < 6; ++e)
        EXPECT_NEAR(f[6 * (i + 1) + e], (fp[e] - fm[e]) / (2 * h), 1e-8) << "triangle " << j << " weight " << i;
    }
  }
}

TEST_P(Features, ReducedEnergyGradientAndHessianMatchFiniteDifferences) {
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes_.rest, 8);
  std::vector<double> targets = meshik_test::gather_rows(meshes_.examples[0], handles);
  for (size_t e = 0; e < targets.size(); ++e) targets[e] += 0.3 * meshes_.examples[1][3 * handles[e / 3] + e % 3];
  std::vector<int> internal_handles;
  for (int h : handles) internal_handles.push_back(impl().internal_of_vertex[h]);
  const meshik::PoseSystem system(impl(), internal_handles);
  meshik::EvaluationBuffers buffers;
  meshik::PoseEvaluator evaluator(impl(), system, GetParam(), 0.5, targets.data(), buffers);
  const std::vector<double> w = {0.6, 0.8, -0.3};
  meshik::PoseEvaluation at, plus, minus;
  evaluator.evaluate(w.data(), true, at);
  evaluator.add_second_order(at);
  const double h = 1e-5;
  for (int i = 0; i < 3; ++i) {
    std::vector<double> wp = w, wm = w;
    wp[i] += h;
    wm[i] -= h;
    evaluator.evaluate(wp.data(), true, plus);
    evaluator.evaluate(wm.data(), true, minus);
    // g = -(1/2) d phi/dw; half the Hessian = S + second-order term = -dg/dw.
    EXPECT_NEAR(at.step_rhs(i), -(plus.energy - minus.energy) / (4 * h), 1e-6 * std::abs(at.energy));
    const Eigen::VectorXd hessian_column = -(plus.step_rhs - minus.step_rhs) / (2 * h);
    const Eigen::VectorXd model_column = (at.schur + at.second_order).col(i);
    EXPECT_LT((hessian_column - model_column).norm(), 1e-5 * model_column.norm()) << "column " << i;
  }
  if (GetParam() == FeatureSpace::kLinear) {
    EXPECT_EQ(at.second_order.norm(), 0.0);  // linear: Gauss-Newton is Newton
  } else {
    EXPECT_GT(at.second_order.norm(), 1e-3 * at.schur.norm());  // the term matters here
  }
}

INSTANTIATE_TEST_SUITE_P(BothFeatureSpaces, Features,
                         ::testing::Values(FeatureSpace::kNonlinear, FeatureSpace::kLinear),
                         [](const auto& info) {
                           return info.param == FeatureSpace::kNonlinear ? "Nonlinear" : "Linear";
                         });

// The tube's three examples, then (for more) partial versions of them: rest + s (example - rest).
ExampleMeshes tube_with_examples(int count) {
  ExampleMeshes meshes = meshik_test::make_tube_examples();
  const std::vector<std::vector<double>> full = meshes.examples;
  for (int i = 3; i < count; ++i) {
    const std::vector<double>& source = full[i % 3];
    std::vector<double> partial(meshes.rest.size());
    const double s = 0.15 + 0.1 * i;
    for (size_t e = 0; e < partial.size(); ++e)
      partial[e] = meshes.rest[e] + s * (source[e] - meshes.rest[e]);
    meshes.examples.push_back(partial);
  }
  return meshes;
}

class FeatureCurvature : public ::testing::TestWithParam<int> {};

// With 3 examples and with 10 (more than one chunk of 8 examples b in the accumulation). The
// term is computed in single precision, so it is held to 1e-5 of the size of its terms.
TEST_P(FeatureCurvature, SecondDerivativesMatchFiniteDifferencesOfTheJacobian) {
  const int k = GetParam();
  const ExampleMeshes meshes = tube_with_examples(k);
  const meshik::ExampleSet set(meshes.view(), meshes.example_pointers());
  const meshik::ExampleFeatures& features = set.impl().features;
  ASSERT_EQ(features.num_batches % meshik::kCurvatureBatches, 1) << "the last batch should come alone";
  std::vector<double> w = {0.9, 1.7, -0.4};
  for (int i = 3; i < k; ++i) w.push_back(0.3 - 0.07 * i);
  std::mt19937 random(9);
  std::normal_distribution<double> normal;
  const int pair_rows = 6 * meshik::kCurvatureBatches;
  std::vector<double> residual(pair_rows * kLanes);
  for (double& r : residual) r = normal(random);
  std::vector<float> scratch(meshik::curvature_scratch_size(k));
  const double h = 1e-6;
  std::vector<int> firsts;  // every third pair, and the last batch alone
  for (int batch = 0; batch + 1 < features.num_batches; batch += 3 * meshik::kCurvatureBatches) firsts.push_back(batch);
  firsts.push_back(features.num_batches - 1);
  for (int batch : firsts) {
    const int last = std::min(batch + meshik::kCurvatureBatches, features.num_batches);
    std::vector<double> curvature(k * k * kLanes, 0.0);
    meshik::add_residual_curvature(features, w.data(), batch, residual.data(), scratch.data(), curvature.data());
    // Expected, per pair and lane: the sum over the batches of <R, (J_a(w + h e_b) - J_a(w - h e_b)) / 2h>,
    // and the sum of the absolute values of its terms (the scale of single-precision rounding).
    std::vector<double> expected(k * k * kLanes, 0.0), scale(k * k * kLanes, 0.0);
    for (int bt = batch; bt < last; ++bt)
      for (int b = 0; b < k; ++b) {
        std::vector<double> plus = w, minus = w, out_plus(meshik::blend_batch_size(k)),
                                              out_minus(out_plus.size());
        plus[b] += h;
        minus[b] -= h;
        meshik::blend_batch(features, FeatureSpace::kNonlinear, plus.data(), bt, out_plus.data());
        meshik::blend_batch(features, FeatureSpace::kNonlinear, minus.data(), bt, out_minus.data());
        for (int a = b; a < k; ++a)  // the function fills the pairs b <= a
          for (int l = 0; l < kLanes; ++l)
            for (int e = 0; e < 6; ++e) {
              const int index = ((a + 1) * 6 + e) * kLanes + l;
              const double term = residual[((bt - batch) * 6 + e) * kLanes + l] *
                                  (out_plus[index] - out_minus[index]) / (2 * h);
              expected[(a * k + b) * kLanes + l] += term;
              scale[(a * k + b) * kLanes + l] += std::abs(term);
            }
      }
    for (int a = 0; a < k; ++a)
      for (int b = 0; b <= a; ++b)
        for (int l = 0; l < kLanes; ++l) {
          const int index = (a * k + b) * kLanes + l;
          EXPECT_NEAR(curvature[index], expected[index], 1e-5 * (1.0 + scale[index]))
              << "batch " << batch << " lane " << l << " pair " << a << "," << b;
        }
  }
}

INSTANTIATE_TEST_SUITE_P(ExampleCounts, FeatureCurvature, ::testing::Values(3, 10));

TEST(FeatureBranches, ATwistBeyondAHalfTurnBlendsHalfWayWithoutUnwinding) {
  // A tube twisted by 1.5 pi: rotations pass a half turn along it. Halfway through the blend the
  // tube must be twisted by 0.75 pi (up to the shear of the twist), not partly unwound the short
  // way round.
  const double pi = 3.14159265358979323846, length = 4.0;
  const ExampleMeshes twisted = meshik_test::make_tube_examples(13, 10, 1.5 * pi);
  const ExampleMeshes half = meshik_test::make_tube_examples(13, 10, 0.75 * pi);
  const double* example = twisted.examples[1].data();  // the twist
  const double w = 0.5;
  const std::vector<double> blended = meshik::ExampleSet(twisted.view(), {example}).blend(&w);
  EXPECT_LT(meshik_test::max_vertex_distance(blended, half.examples[1]), 0.05 * length);
  EXPECT_EQ(meshik_test::count_flipped_triangles(blended, half.examples[1], twisted.triangles), 0);

  // The same blend from the principal logs (no branch choice) unwinds the far end and flips.
  meshik::ExampleSet principal(twisted.view(), {example});
  meshik_test::use_principal_logs(principal, {example});
  const std::vector<double> unwound = principal.blend(&w);
  EXPECT_GT(meshik_test::rms_vertex_distance(unwound, half.examples[1]), 0.1 * length);
  EXPECT_GT(meshik_test::count_flipped_triangles(unwound, half.examples[1], twisted.triangles), 10);
}

}  // namespace
