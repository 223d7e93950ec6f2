// The rule of issue 13 for features stored in single precision (FeaturePrecision::kSingle), on the
// horse of ../shared/data (skipped when absent): the examples still reproduce to < 1e-6 of the
// bounding-box diagonal, held-out poses' errors stay within 1e-4 relative of those with features
// stored in double, and the poses are the same bits for any thread count in both precisions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "test_meshik_support.h"

namespace {

using meshik::FeaturePrecision;
using meshik::FeatureSpace;

constexpr FeaturePrecision kPrecisions[] = {FeaturePrecision::kSingle, FeaturePrecision::kDouble};

const char* name_of(FeaturePrecision precision) {
  return precision == FeaturePrecision::kSingle ? "single" : "double";
}

// The pose of `space` from the 16 farthest-point handles (as in the paper-table benchmark) of
// `pose` (#V by 3), with the examples' features stored in `precision`, on `threads` threads.
meshik::SolveResult pose_from_handles(const meshik_test::ExampleMeshes& meshes, const std::vector<double>& pose,
                                      FeaturePrecision precision, FeatureSpace space, int threads = 0) {
  const auto set = std::make_shared<meshik::ExampleSet>(meshes.view(), meshes.example_pointers(),
                                                        meshik::ProgressCallback{}, threads, precision);
  EXPECT_EQ(set->feature_precision(), precision);
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 16);
  meshik::SolverOptions options;
  options.feature_space = space;
  options.threads = threads;
  return meshik::Solver(set, handles, options).solve(meshik_test::gather_rows(pose, handles).data());
}

TEST(FeaturePrecision, SingleFeaturesReproduceTheHorsesExamples) {
  LOAD_OR_SKIP(meshes, "horse-poses", "reference.obj", {"1.obj", "2.obj", "3.obj", "4.obj"});
  const double diagonal = meshik_test::bounding_box_diagonal(meshes.rest);
  for (FeatureSpace space : {FeatureSpace::kNonlinear, FeatureSpace::kLinear}) {
    double worst = 0.0;
    for (size_t i = 0; i < meshes.examples.size(); ++i) {
      const meshik::SolveResult pose =
          pose_from_handles(meshes, meshes.examples[i], FeaturePrecision::kSingle, space);
      const double error = meshik_test::max_vertex_distance(pose.vertices, meshes.examples[i]);
      EXPECT_LT(error, 1e-6 * diagonal) << "example " << i;
      worst = std::max(worst, error);
    }
    std::printf("%s space, single-precision features: examples reproduced to %.2e of the diagonal\n",
                space == FeatureSpace::kNonlinear ? "nonlinear" : "linear", worst / diagonal);
  }
}

TEST(FeaturePrecision, HeldOutErrorsStayWithin1e4RelativeOfDoubleFeatures) {
  LOAD_OR_SKIP(meshes, "horse-poses", "reference.obj", {"1.obj", "2.obj", "3.obj", "4.obj"});
  for (const char* held_out_name : {"5.obj", "7.obj"}) {
    const std::vector<double> held_out = meshik_bench::read_obj(data_dir + "/horse-poses/" + held_out_name).vertices;
    for (FeatureSpace space : {FeatureSpace::kNonlinear, FeatureSpace::kLinear}) {
      double rms[2], largest[2];
      for (int p = 0; p < 2; ++p) {
        const meshik::SolveResult pose = pose_from_handles(meshes, held_out, kPrecisions[p], space);
        EXPECT_TRUE(pose.converged) << held_out_name << ", " << name_of(kPrecisions[p]);
        rms[p] = meshik_test::rms_vertex_distance(pose.vertices, held_out);
        largest[p] = meshik_test::max_vertex_distance(pose.vertices, held_out);
      }
      EXPECT_LE(std::abs(rms[0] - rms[1]), 1e-4 * rms[1]) << held_out_name;
      EXPECT_LE(std::abs(largest[0] - largest[1]), 1e-4 * largest[1]) << held_out_name;
      std::printf("%s, %s space: RMS error single %.9f double %.9f (relative change %.1e), largest single %.9f "
                  "double %.9f (%.1e)\n",
                  held_out_name, space == FeatureSpace::kNonlinear ? "nonlinear" : "linear", rms[0], rms[1],
                  std::abs(rms[0] - rms[1]) / rms[1], largest[0], largest[1],
                  std::abs(largest[0] - largest[1]) / largest[1]);
    }
  }
}

TEST(FeaturePrecision, AnyThreadCountGivesTheSameBitsInBothPrecisions) {
  LOAD_OR_SKIP(meshes, "horse-poses", "reference.obj", {"1.obj", "2.obj", "3.obj", "4.obj"});
  const std::vector<double> held_out = meshik_bench::read_obj(data_dir + "/horse-poses/5.obj").vertices;
  for (FeaturePrecision precision : kPrecisions) {
    const meshik::SolveResult serial = pose_from_handles(meshes, held_out, precision, FeatureSpace::kNonlinear, 1);
    ASSERT_GE(serial.iterations, 1);
    for (int threads : {2, 3}) {
      const meshik::SolveResult other =
          pose_from_handles(meshes, held_out, precision, FeatureSpace::kNonlinear, threads);
      EXPECT_EQ(other.vertices, serial.vertices) << name_of(precision) << ", " << threads << " threads";
      EXPECT_EQ(other.weights, serial.weights) << name_of(precision) << ", " << threads << " threads";
      EXPECT_EQ(other.energies, serial.energies) << name_of(precision) << ", " << threads << " threads";
    }
  }
}

}  // namespace
