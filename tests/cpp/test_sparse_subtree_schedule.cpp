// The split of the supernodal tree for the factorization and the backward solve: every supernode
// once, on top or in exactly one subtree, each subtree closed under descendants with its ancestors
// all on top, stacks of sizes within bounds, and a mesh's tree split into several subtrees.
#include <gtest/gtest.h>

#include <vector>

#include "../../bench/normal_matrix.h"
#include "../../bench/sphere_mesh.h"
#include "sparse/analysis.h"
#include "sparse/subtree_schedule.h"
#include "sparse_test_matrices.h"

namespace {

using meshik::sparse::SubtreeSchedule;
using meshik::sparse::SymbolicFactor;

// Expects schedule to split f's supernodes as described above.
void expect_valid_split(const SymbolicFactor& f, const SubtreeSchedule& schedule) {
  const int count = f.num_supernodes();
  std::vector<int> owner(count, -2);  // -1: top, t: subtree t
  for (int s : schedule.top) {
    ASSERT_EQ(owner[s], -2) << "supernode " << s << " twice";
    owner[s] = -1;
  }
  ASSERT_EQ(schedule.first.size(), schedule.root.size());
  ASSERT_EQ(schedule.stack.size(), schedule.root.size());
  EXPECT_LE(schedule.top_stack, f.stack_size);
  for (size_t t = 0; t < schedule.root.size(); ++t) {
    for (int s = schedule.first[t]; s <= schedule.root[t]; ++s) {
      ASSERT_EQ(owner[s], -2) << "supernode " << s << " twice";
      owner[s] = static_cast<int>(t);
    }
    // A subtree's stack holds at least its root's update matrix, at most the whole tree's stack.
    const int root = schedule.root[t];
    const int k = f.first_column[root + 1] - f.first_column[root];
    EXPECT_GE(schedule.stack[t], meshik::sparse::packed_size(f.row_start[root + 1] - f.row_start[root] - k));
    EXPECT_LE(schedule.stack[t], f.stack_size);
  }
  for (int s = 0; s < count; ++s) {
    ASSERT_NE(owner[s], -2) << "supernode " << s << " missing";
    const int p = f.parent[s];
    if (owner[s] == -1) {
      if (p >= 0) EXPECT_EQ(owner[p], -1) << "a top supernode's parent is on top";
    } else if (s != schedule.root[owner[s]]) {
      EXPECT_EQ(owner[p], owner[s]) << "supernode " << s << " leaves its subtree below its root";
    } else if (p >= 0) {
      EXPECT_EQ(owner[p], -1) << "a subtree root's parent is on top";
    }
  }
}

TEST(SparseSubtreeSchedule, SplitsAMeshTreeIntoIndependentSubtrees) {
  const auto sphere = meshik_bench::geodesic_sphere(16);
  const meshik::CscMatrix a =
      meshik_bench::deformation_normal_matrix(sphere, meshik_bench::spread_handles(sphere.num_vertices(), 12), false);
  const auto analysis = meshik::sparse::analyze_pattern(a);
  const SubtreeSchedule schedule = meshik::sparse::subtree_schedule(analysis.symbolic, 4);
  expect_valid_split(analysis.symbolic, schedule);
  EXPECT_GE(schedule.root.size(), 4u);
  const SubtreeSchedule for_two = meshik::sparse::subtree_schedule(analysis.symbolic, 2);
  expect_valid_split(analysis.symbolic, for_two);
  EXPECT_GE(for_two.root.size(), 2u);
}

TEST(SparseSubtreeSchedule, SmallAndDenseTreesAreValidToo) {
  for (const meshik::CscMatrix& a : {meshik_test::grid_laplacian(31, 27, 0.1),
                                     meshik_test::lower_from_dense(meshik_test::random_spd(40, 0.1, 7))}) {
    const auto analysis = meshik::sparse::analyze_pattern(a);
    expect_valid_split(analysis.symbolic, meshik::sparse::subtree_schedule(analysis.symbolic, 4));
  }
}

}  // namespace
