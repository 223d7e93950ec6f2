// Symbolic analysis (elimination tree, postorder, column counts) against a brute-force
// symbolic elimination on dense boolean matrices.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "sparse/column_counts.h"
#include "sparse/elimination_tree.h"
#include "sparse/permuted_matrix.h"

using namespace meshik::sparse;

namespace {

// A random symmetric boolean n by n pattern with the given off-diagonal density, diagonal set.
std::vector<std::vector<bool>> random_pattern(int n, double density, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  std::vector<std::vector<bool>> a(n, std::vector<bool>(n, false));
  for (int j = 0; j < n; ++j) {
    a[j][j] = true;
    for (int i = j + 1; i < n; ++i) a[i][j] = a[j][i] = coin(rng) < density;
  }
  return a;
}

// Lower (rows >= col) or upper (rows <= col) triangle of a boolean pattern as a Pattern.
Pattern triangle(const std::vector<std::vector<bool>>& a, bool lower) {
  Pattern p;
  p.n = static_cast<int>(a.size());
  p.col_start.push_back(0);
  for (int j = 0; j < p.n; ++j) {
    for (int i = 0; i < p.n; ++i)
      if (a[i][j] && (lower ? i >= j : i <= j)) p.row_index.push_back(i);
    p.col_start.push_back(static_cast<int>(p.row_index.size()));
  }
  return p;
}

// Structure of L by symbolic elimination: L(i, j) != 0 for i > j iff A(i, j) != 0 or
// L(i, k) and L(j, k) != 0 for some k < j. Returns the n by n boolean lower triangle.
std::vector<std::vector<bool>> symbolic_factor(std::vector<std::vector<bool>> l) {
  const int n = static_cast<int>(l.size());
  for (int k = 0; k < n; ++k)
    for (int j = k + 1; j < n; ++j)
      if (l[j][k])
        for (int i = j + 1; i < n; ++i)
          if (l[i][k]) l[i][j] = true;
  return l;
}

}  // namespace

TEST(SparseSymbolic, EliminationTreeAndCountsMatchBruteForce) {
  unsigned seed = 1;
  for (int n : {1, 2, 5, 12, 40, 90})
    for (double density : {0.0, 0.03, 0.1, 0.4, 1.0}) {
      SCOPED_TRACE("n=" + std::to_string(n) + " density=" + std::to_string(density));
      const auto a = random_pattern(n, density, seed++);
      const auto l = symbolic_factor(a);
      const std::vector<int> parent = elimination_tree(triangle(a, false));
      const std::vector<int> post = tree_postorder(parent);
      const std::vector<int> counts = column_counts(triangle(a, true), parent, post);
      for (int j = 0; j < n; ++j) {
        // parent[j]: the first off-diagonal row of column j of L.
        int first_row = -1, count = 1;
        for (int i = n - 1; i > j; --i)
          if (l[i][j]) {
            first_row = i;
            ++count;
          }
        EXPECT_EQ(parent[j], first_row) << "column " << j;
        EXPECT_EQ(counts[j], count) << "column " << j;
      }
    }
}

TEST(SparseSymbolic, PostorderVisitsDescendantsFirstAndContiguously) {
  // A forest: 0,1 -> 2; 3 -> 4; 2,4 -> 6; 5 alone; 7 -> 8.
  const std::vector<int> parent = {2, 2, 6, 4, 6, -1, -1, 8, -1};
  const std::vector<int> post = tree_postorder(parent);
  ASSERT_EQ(post.size(), parent.size());
  std::vector<int> position(parent.size(), -1);
  for (size_t k = 0; k < post.size(); ++k) {
    ASSERT_EQ(position[post[k]], -1) << "node visited twice";
    position[post[k]] = static_cast<int>(k);
  }
  for (size_t j = 0; j < parent.size(); ++j)
    if (parent[j] != -1) EXPECT_LT(position[j], position[parent[j]]);
  // The subtree of 6 is {0, 1, 2, 3, 4, 6}: six consecutive positions ending at 6's.
  for (int j : {0, 1, 2, 3, 4}) EXPECT_GE(position[j], position[6] - 5);
}

TEST(SparseSymbolic, TransposeSortsRows) {
  const auto a = random_pattern(30, 0.2, 5);
  const Pattern upper = triangle(a, false);
  const Pattern lower = triangle(a, true);
  const Pattern t = transpose(upper);
  EXPECT_EQ(t.col_start, lower.col_start);
  EXPECT_EQ(t.row_index, lower.row_index);
}
