// Soft handles (SolverOptions::handle_stiffness): a large stiffness approaches the hard pose, a
// small one keeps the examples' shape (no spike) when one target is out of reach, reachable
// targets are met exactly, and a stiffness of 0 is the hard solve bit for bit.
#include <gtest/gtest.h>

#include <memory>

#include "test_meshik_support.h"

namespace {

using meshik::ExampleSet;
using meshik::SolveResult;
using meshik::Solver;
using meshik::SolverOptions;

class SoftHandles : public ::testing::Test {
 protected:
  void SetUp() override {
    // Example 0's handle positions, the first handle pulled 0.3 diagonals out of reach sideways.
    targets_ = meshik_test::gather_rows(tube_.meshes.examples[0], tube_.handles);
    pull_ = 0.3 * tube_.diagonal;
    targets_[0] += pull_;
  }
  SolveResult solve(double stiffness, const std::vector<double>& targets) const {
    SolverOptions options;
    options.handle_stiffness = stiffness;
    return Solver(set_, handles_, options).solve(targets.data());
  }
  // Largest distance of pose from example 0 after removing their mean offset (a translation).
  double shape_change(const std::vector<double>& pose) const {
    const std::vector<double>& example = meshes_.examples[0];
    const size_t n = example.size() / 3;
    double mean[3] = {0.0, 0.0, 0.0};
    for (size_t v = 0; v < n; ++v)
      for (int c = 0; c < 3; ++c) mean[c] += (pose[3 * v + c] - example[3 * v + c]) / n;
    std::vector<double> moved(pose);
    for (size_t v = 0; v < n; ++v)
      for (int c = 0; c < 3; ++c) moved[3 * v + c] -= mean[c];
    return meshik_test::max_vertex_distance(moved, example);
  }
  const meshik_test::TubeProblem tube_ = meshik_test::make_tube_problem();
  const meshik_test::ExampleMeshes& meshes_ = tube_.meshes;
  const std::shared_ptr<ExampleSet>& set_ = tube_.set;
  const std::vector<int>& handles_ = tube_.handles;
  const double diagonal_ = tube_.diagonal;
  std::vector<double> targets_;
  double pull_ = 0.0;
};

TEST_F(SoftHandles, ZeroStiffnessIsTheHardSolveBitForBit) {
  const SolveResult hard = Solver(set_, handles_).solve(targets_.data());
  const SolveResult zero = solve(0.0, targets_);
  EXPECT_EQ(hard.vertices, zero.vertices);
  EXPECT_EQ(hard.weights, zero.weights);
  EXPECT_EQ(hard.residual, zero.residual);
  const int h = handles_[0];
  for (int c = 0; c < 3; ++c) EXPECT_EQ(hard.vertices[3 * h + c], targets_[c]);
}

TEST_F(SoftHandles, ReachableTargetsAreMetExactly) {
  const std::vector<double> reachable = meshik_test::gather_rows(meshes_.examples[1], handles_);
  const SolveResult soft = solve(0.01, reachable);
  EXPECT_LT(meshik_test::max_vertex_distance(soft.vertices, meshes_.examples[1]), 1e-6 * diagonal_);
  EXPECT_LT(soft.residual, 1e-12);
}

TEST_F(SoftHandles, LargeStiffnessApproachesTheHardPose) {
  const SolveResult hard = solve(0.0, targets_);
  double previous = 1e300;
  for (double stiffness : {1e2, 1e4, 1e6}) {
    const SolveResult soft = solve(stiffness, targets_);
    const double distance = meshik_test::max_vertex_distance(soft.vertices, hard.vertices);
    EXPECT_LT(distance, previous) << "stiffness " << stiffness;
    previous = distance;
  }
  EXPECT_LT(previous, 1e-4 * diagonal_);
}

TEST_F(SoftHandles, SmallStiffnessKeepsTheExamplesShapeInsteadOfASpike) {
  const SolveResult hard = solve(0.0, targets_);
  const SolveResult soft = solve(1e-4, targets_);
  // Hard: the handle vertex alone follows its target, a spike of most of the pull.
  EXPECT_GT(shape_change(hard.vertices), 0.5 * pull_);
  // Soft: the shape stays example 0's (moved as a whole), the handle short of its target.
  EXPECT_LT(shape_change(soft.vertices), 0.01 * pull_);
  const int h = handles_[0];
  EXPECT_GT(std::abs(soft.vertices[3 * h] - targets_[0]), 0.5 * pull_);
  EXPECT_TRUE(soft.inverted_triangles.empty());
}

TEST_F(SoftHandles, ANegativeOrNonFiniteStiffnessIsRefused) {
  SolverOptions options;
  options.handle_stiffness = -1.0;
  EXPECT_THROW(Solver(set_, handles_, options), meshik::InputError);
  options.handle_stiffness = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Solver(set_, handles_, options), meshik::InputError);
}

}  // namespace
