// The handle system's work beside its factorization: the callback sees the rows numbered and the
// partition built, the linear start assembled there equals the one assembled after the
// factorization to the bit, and what the callback throws is thrown by the constructor.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "example_set_impl.h"
#include "linear_start.h"
#include "pose_evaluation.h"
#include "pose_system.h"
#include "test_meshik_support.h"

namespace {

// The problem's handles as internal vertex indices (what PoseSystem takes).
std::vector<int> internal_handles(const meshik_test::TubeProblem& problem) {
  std::vector<int> internal;
  for (int v : problem.handles) internal.push_back(problem.set->impl().internal_of_vertex[v]);
  return internal;
}

TEST(PoseSystem, TheLinearStartAssembledBesideTheFactorizationIsTheSameBits) {
  const meshik_test::TubeProblem problem = meshik_test::make_tube_problem();
  const meshik::ExampleSet::Impl& set = problem.set->impl();
  const std::vector<int> handles = internal_handles(problem);
  const std::vector<double> targets = meshik_test::gather_rows(problem.meshes.examples[1], problem.handles);
  // After: the one-step constructor on one thread.
  const meshik::PoseSystem after(set, handles);
  meshik::EvaluationBuffers after_buffers;
  const Eigen::VectorXd expected = meshik::LinearStart(set, after, after_buffers).weights(targets.data(), 0.0);
  ASSERT_GT(expected.size(), 0);
  // Beside: assembled on the extra thread while a team of 2 factors.
  meshik::EvaluationBuffers buffers;
  meshik::LinearStartAssembly assembly;
  int chunks_seen = 0;
  std::vector<int> rows_seen;
  const meshik::PoseSystem beside(set, handles, {}, 2, 0.0, [&](const meshik::PoseSystem& system) {
    chunks_seen = system.partition().num_chunks();
    rows_seen = system.unknown_of_vertex();
    assembly = meshik::assemble_linear_start(set, system, buffers, 1);
  });
  EXPECT_EQ(chunks_seen, beside.partition().num_chunks());
  EXPECT_EQ(rows_seen, beside.unknown_of_vertex());  // already in the factor's order
  EXPECT_EQ(rows_seen, after.unknown_of_vertex());
  const Eigen::VectorXd weights = meshik::LinearStart(set, beside, std::move(assembly), 2).weights(targets.data(), 0.0);
  ASSERT_EQ(weights.size(), expected.size());
  for (Eigen::Index i = 0; i < weights.size(); ++i) EXPECT_EQ(weights(i), expected(i)) << "weight " << i;
}

TEST(PoseSystem, AnErrorBesideTheFactorizationIsThrownByTheConstructor) {
  const meshik_test::TubeProblem problem = meshik_test::make_tube_problem();
  for (int team : {1, 2}) {
    EXPECT_THROW(meshik::PoseSystem(problem.set->impl(), internal_handles(problem), {}, team, 0.0,
                                    [](const meshik::PoseSystem&) { throw std::runtime_error("beside"); }),
                 std::runtime_error)
        << team << " threads";
  }
}

}  // namespace
