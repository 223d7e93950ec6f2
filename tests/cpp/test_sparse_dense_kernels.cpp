// The supernodal factorization's dense kernels on a team of threads (node-level parallelism):
// the same bits as on one thread for any team, on panels large enough to be split, and a correct
// factor (L L^T equals the panel's matrix).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

#include "sparse/dense_kernels.h"
#include "sparse_test_matrices.h"

namespace {

// A rows by cols panel (column-major): the first cols columns of a random SPD rows by rows matrix.
std::vector<double> spd_panel(int rows, int cols, unsigned seed) {
  const Eigen::MatrixXd a = meshik_test::random_spd(rows, 1.0, seed);
  return std::vector<double>(a.data(), a.data() + static_cast<long>(rows) * cols);
}

TEST(SparseDenseKernels, PanelFactorGivesTheSameBitsOnAnyTeam) {
  // 1,100 rows: the rows below each 32-column block are shared out, and so are the later columns.
  const int rows = 1100, cols = 300;
  const std::vector<double> panel = spd_panel(rows, cols, 3);
  std::vector<double> serial = panel;
  ASSERT_EQ(meshik::sparse::factor_panel(serial.data(), rows, cols, 1), -1);
  // L11 L11^T is the top block, L21 L11^T the rows below it.
  const Eigen::Map<const Eigen::MatrixXd> a(panel.data(), rows, cols), l(serial.data(), rows, cols);
  const Eigen::MatrixXd l11 = l.topRows(cols).triangularView<Eigen::Lower>();
  EXPECT_LT((l11 * l11.transpose() - a.topRows(cols)).lpNorm<Eigen::Infinity>(), 1e-9 * a.lpNorm<Eigen::Infinity>());
  EXPECT_LT((l.bottomRows(rows - cols) * l11.transpose() - a.bottomRows(rows - cols)).lpNorm<Eigen::Infinity>(),
            1e-9 * a.lpNorm<Eigen::Infinity>());
  for (int team : {2, 3, 5}) {
    std::vector<double> x = panel;
    ASSERT_EQ(meshik::sparse::factor_panel(x.data(), rows, cols, team), -1);
    EXPECT_EQ(x, serial) << team << " threads";
  }
}

TEST(SparseDenseKernels, PanelFactorNamesTheSameFailingColumnOnAnyTeam) {
  const int rows = 1100, cols = 200;
  std::vector<double> panel = spd_panel(rows, cols, 4);
  panel[static_cast<long>(77) * rows + 77] = -1.0;
  for (int team : {1, 2, 3}) {
    std::vector<double> x = panel;
    EXPECT_EQ(meshik::sparse::factor_panel(x.data(), rows, cols, team), 77) << team << " threads";
  }
}

TEST(SparseDenseKernels, UpdateMatrixGivesTheSameBitsOnAnyTeam) {
  // U = -L21 L21^T of a 700 by 150 L21 (its columns in chunks of 64: each piece of U's columns
  // sums them in the same order).
  const int m = 700, k = 150, ld = m + 9;
  const std::vector<double> l21 = meshik_test::random_values(static_cast<size_t>(ld) * k, 5);
  const size_t packed = static_cast<size_t>(m) * (m + 1) / 2;
  std::vector<double> serial(packed);
  meshik::sparse::negative_lower_product(l21.data(), ld, m, k, serial.data(), 1);
  const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> l(l21.data(), m, k, Eigen::OuterStride<>(ld));
  const Eigen::MatrixXd expected = -l * l.transpose();
  for (int q : {0, 1, 350, m - 1})
    for (int p : {q, (q + m) / 2, m - 1})
      EXPECT_NEAR(serial[meshik::sparse::packed_column_offset(m, q) + p - q], expected(p, q), 1e-10 * k);
  for (int team : {2, 3, 5}) {
    std::vector<double> u(packed);
    meshik::sparse::negative_lower_product(l21.data(), ld, m, k, u.data(), team);
    EXPECT_EQ(u, serial) << team << " threads";
  }
}

}  // namespace
