// SparseCholesky against Eigen's dense LLT on random SPD matrices, on grid Laplacians, with
// many right-hand sides, refactorization, and its errors.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "meshik/sparse_cholesky.h"
#include "sparse_test_matrices.h"

using meshik::CscMatrix;
using meshik::SparseCholesky;
using namespace meshik_test;

namespace {

// Solves the dense SPD system with `nrhs` random right-hand sides through SparseCholesky and
// through Eigen's dense LLT; expects the same solutions and a small residual.
void expect_matches_dense(const Eigen::MatrixXd& dense, int nrhs, unsigned seed) {
  const int n = static_cast<int>(dense.rows());
  const CscMatrix a = lower_from_dense(dense);
  SparseCholesky chol;
  chol.compute(a);
  ASSERT_EQ(chol.size(), n);
  const std::vector<double> b = random_values(static_cast<size_t>(n) * nrhs, seed);
  std::vector<double> x = b;
  chol.solve(x.data(), nrhs);
  // Eigen: column-major n x nrhs from our row-major buffer.
  const Eigen::MatrixXd b_dense =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          b.data(), n, nrhs);
  const Eigen::MatrixXd x_dense = dense.llt().solve(b_dense);
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < nrhs; ++r)
      worst = std::max(worst, std::abs(x[static_cast<size_t>(i) * nrhs + r] - x_dense(i, r)));
  EXPECT_LT(worst, 1e-10 * std::max(1.0, x_dense.cwiseAbs().maxCoeff())) << "n=" << n;
  EXPECT_LT(relative_residual(a, x, b, nrhs), 1e-10) << "n=" << n;
}

}  // namespace

TEST(SparseCholesky, RandomMatricesMatchDenseLLT) {
  unsigned seed = 1;
  for (int n : {1, 2, 3, 4, 7, 16, 33, 64, 120, 200})
    for (double density : {0.0, 0.02, 0.1, 0.3, 1.0}) {
      SCOPED_TRACE("n=" + std::to_string(n) + " density=" + std::to_string(density));
      expect_matches_dense(random_spd(n, density, seed), 3, seed + 1000);
      ++seed;
    }
}

TEST(SparseCholesky, DiagonalMatrix) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(50, 50);
  for (int i = 0; i < 50; ++i) d(i, i) = 1.0 + i;
  expect_matches_dense(d, 2, 7);
  SparseCholesky chol;
  chol.compute(lower_from_dense(d));
  EXPECT_EQ(chol.factor_nonzeros(), 50);
}

TEST(SparseCholesky, DenseMatrixHasFullFactor) {
  const int n = 40;
  const Eigen::MatrixXd dense = random_spd(n, 1.0, 11);
  expect_matches_dense(dense, 5, 12);
  SparseCholesky chol;
  chol.compute(lower_from_dense(dense));
  EXPECT_EQ(chol.factor_nonzeros(), n * (n + 1) / 2);
}

TEST(SparseCholesky, DisconnectedBlocks) {
  const int blocks = 5, block = 17;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(blocks * block, blocks * block);
  for (int k = 0; k < blocks; ++k)
    dense.block(k * block, k * block, block, block) = random_spd(block, 0.4, 20 + k);
  expect_matches_dense(dense, 4, 30);
}

TEST(SparseCholesky, OverlappingDenseBlocks) {
  // Two dense 100 x 100 blocks sharing 10 unknowns: supernodes of about 90 columns with rows
  // below them, so the blocked panel and the chunked update product are exercised.
  const int block = 100, shared = 10, n = 2 * block - shared;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  dense.topLeftCorner(block, block) += random_spd(block, 1.0, 41);
  dense.bottomRightCorner(block, block) += random_spd(block, 1.0, 42);
  expect_matches_dense(dense, 5, 43);
}

TEST(SparseCholesky, EmptyMatrix) {
  CscMatrix a;
  a.col_start = {0};
  SparseCholesky chol;
  chol.compute(a);
  EXPECT_EQ(chol.size(), 0);
  EXPECT_EQ(chol.factor_nonzeros(), 0);
  chol.solve(nullptr, 3);
}

TEST(SparseCholesky, GridLaplacianResidual) {
  const CscMatrix a = grid_laplacian(70, 60, 1e-2);
  SparseCholesky chol;
  chol.compute(a);
  const int nrhs = 15;
  const std::vector<double> b = random_values(static_cast<size_t>(a.rows) * nrhs, 3);
  std::vector<double> x = b;
  chol.solve(x.data(), nrhs);
  EXPECT_LT(relative_residual(a, x, b, nrhs), 1e-10);
  // Fill-reducing ordering: far below the dense triangle, above nnz(A).
  EXPECT_GT(chol.factor_nonzeros(), static_cast<long long>(a.row_index.size()));
  EXPECT_LT(chol.factor_nonzeros(), 40LL * a.rows);
}

TEST(SparseCholesky, ManyRightHandSidesEqualOneAtATime) {
  const CscMatrix a = grid_laplacian(23, 19, 0.1);
  SparseCholesky chol;
  chol.compute(a);
  const int n = a.rows;
  for (int nrhs : {1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33}) {
    const std::vector<double> b = random_values(static_cast<size_t>(n) * nrhs, 100 + nrhs);
    std::vector<double> together = b;
    chol.solve(together.data(), nrhs);
    for (int r = 0; r < nrhs; ++r) {
      std::vector<double> single(n);
      for (int i = 0; i < n; ++i) single[i] = b[static_cast<size_t>(i) * nrhs + r];
      chol.solve(single.data(), 1);
      for (int i = 0; i < n; ++i)
        ASSERT_NEAR(together[static_cast<size_t>(i) * nrhs + r], single[i], 1e-12 * (1 + std::abs(single[i])))
            << "nrhs=" << nrhs << " rhs " << r << " row " << i;
    }
  }
}

TEST(SparseCholesky, RefactorizeWithNewValuesSamePattern) {
  CscMatrix a = grid_laplacian(30, 25, 0.5);
  SparseCholesky chol;
  chol.analyze(a);
  const long long nnz = chol.factor_nonzeros();
  for (int round = 0; round < 3; ++round) {
    // New values: scale the off-diagonals and raise the shift.
    const std::vector<double> noise = random_values(a.values.size(), 50 + round);
    for (int j = 0; j < a.cols; ++j)
      for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p)
        if (a.row_index[p] != j) a.values[p] = -0.5 - 0.4 * noise[p];
    for (int j = 0; j < a.cols; ++j) a.values[a.col_start[j]] = 4.0 + round;  // diagonal first
    chol.factorize(a);
    EXPECT_EQ(chol.factor_nonzeros(), nnz);
    const std::vector<double> b = random_values(static_cast<size_t>(a.rows) * 2, 60 + round);
    std::vector<double> x = b;
    chol.solve(x.data(), 2);
    EXPECT_LT(relative_residual(a, x, b, 2), 1e-10) << "round " << round;
  }
}

TEST(SparseCholesky, EntriesAboveTheDiagonalAreIgnored) {
  const Eigen::MatrixXd dense = random_spd(60, 0.1, 77);
  const CscMatrix lower = lower_from_dense(dense);
  // Full storage of the same matrix, with garbage values above the diagonal.
  CscMatrix full;
  full.rows = full.cols = 60;
  full.col_start.push_back(0);
  for (int j = 0; j < 60; ++j) {
    for (int i = 0; i < 60; ++i)
      if (i == j || dense(i, j) != 0.0) {
        full.row_index.push_back(i);
        full.values.push_back(i < j ? 1e6 : dense(i, j));
      }
    full.col_start.push_back(static_cast<int>(full.row_index.size()));
  }
  SparseCholesky from_lower, from_full;
  from_lower.compute(lower);
  from_full.compute(full);
  std::vector<double> x1 = random_values(60, 5), x2 = x1;
  from_lower.solve(x1.data(), 1);
  from_full.solve(x2.data(), 1);
  for (int i = 0; i < 60; ++i) EXPECT_NEAR(x1[i], x2[i], 1e-12);
}

TEST(SparseCholesky, IndefiniteMatrixNamesTheColumn) {
  // Diagonal with one negative entry: every ordering fails at that column.
  Eigen::MatrixXd d = Eigen::MatrixXd::Identity(20, 20);
  d(13, 13) = -2.0;
  SparseCholesky chol;
  try {
    chol.compute(lower_from_dense(d));
    FAIL() << "expected NotPositiveDefinite";
  } catch (const meshik::NotPositiveDefinite& e) {
    EXPECT_NE(std::string(e.what()).find("column 13"), std::string::npos) << e.what();
  }
  // A coupled indefinite matrix: [[1, 2], [2, 1]] fails at the second pivot.
  Eigen::MatrixXd c(2, 2);
  c << 1, 2, 2, 1;
  EXPECT_THROW(chol.compute(lower_from_dense(c)), meshik::NotPositiveDefinite);
  // No solve after a failed factorization.
  std::vector<double> b(2, 1.0);
  EXPECT_THROW(chol.solve(b.data(), 1), std::logic_error);
}

TEST(SparseCholesky, NegativePivotInADenseBlockNamesItsColumn) {
  // Every principal submatrix without column 77 is positive definite (diagonally dominant),
  // so whatever the order, the first pivot that fails is column 77's, inside one supernode
  // of 100 columns (the blocked panel factorization).
  Eigen::MatrixXd dense = random_spd(100, 1.0, 5);
  dense(77, 77) = -50.0;
  SparseCholesky chol;
  try {
    chol.compute(lower_from_dense(dense));
    FAIL() << "expected NotPositiveDefinite";
  } catch (const meshik::NotPositiveDefinite& e) {
    EXPECT_NE(std::string(e.what()).find("column 77 "), std::string::npos) << e.what();
  }
}

TEST(SparseCholesky, IndefiniteLaplacianIsRejected) {
  // Graph Laplacian shifted below zero: its smallest eigenvalue is -0.05.
  const CscMatrix a = grid_laplacian(6, 5, -0.05);
  SparseCholesky chol;
  EXPECT_THROW(chol.compute(a), meshik::NotPositiveDefinite);
}

TEST(SparseCholesky, InvalidInputIsNamed) {
  SparseCholesky chol;
  CscMatrix a = lower_from_dense(random_spd(5, 0.5, 3));
  CscMatrix not_square = a;
  not_square.rows = 6;
  EXPECT_THROW(chol.analyze(not_square), std::invalid_argument);
  CscMatrix out_of_range = a;
  out_of_range.row_index.back() = 9;
  try {
    chol.analyze(out_of_range);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("column 4"), std::string::npos) << e.what();
  }
  CscMatrix no_diagonal;
  no_diagonal.rows = no_diagonal.cols = 2;
  no_diagonal.col_start = {0, 1, 2};
  no_diagonal.row_index = {1, 1};
  no_diagonal.values = {1.0, 1.0};
  try {
    chol.analyze(no_diagonal);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("column 0 has no diagonal"), std::string::npos) << e.what();
  }
  CscMatrix unsorted = lower_from_dense(random_spd(4, 1.0, 9));
  std::swap(unsorted.row_index[1], unsorted.row_index[2]);
  EXPECT_THROW(chol.analyze(unsorted), std::invalid_argument);
}

// One analysis, several factorizations of its pattern with other values, each independent.
TEST(SparseCholesky, SharedAnalysisFactorsOtherValuesOfThePattern) {
  const CscMatrix a = grid_laplacian(9, 7, 0.5);
  const CscMatrix b = grid_laplacian(9, 7, 2.0);  // same pattern, other values
  const int n = a.rows, nrhs = 5;
  SparseCholesky first, second;
  first.analyze(a);
  second.share_analysis(first);
  EXPECT_EQ(second.permutation(), first.permutation());
  EXPECT_EQ(second.factor_nonzeros(), first.factor_nonzeros());
  first.factorize(a);
  second.factorize(b);
  const std::vector<double> rhs = random_values(static_cast<size_t>(n) * nrhs, 4);
  std::vector<double> x = rhs, y = rhs;
  first.solve(x.data(), nrhs);
  second.solve(y.data(), nrhs);
  EXPECT_LT(relative_residual(a, x, rhs, nrhs), 1e-12);
  EXPECT_LT(relative_residual(b, y, rhs, nrhs), 1e-12);

  SparseCholesky unanalysed, sharer;
  EXPECT_THROW(sharer.share_analysis(unanalysed), std::logic_error);
  EXPECT_THROW(unanalysed.factorize(a), std::logic_error);
  sharer.share_analysis(first);
  EXPECT_THROW(sharer.factorize(grid_laplacian(9, 8, 0.5)), std::invalid_argument);
  EXPECT_THROW(sharer.solve(x.data(), nrhs), std::logic_error);  // analysed, not factored
}

TEST(SparseCholesky, FactorizeRejectsAnotherPattern) {
  SparseCholesky chol;
  chol.analyze(grid_laplacian(5, 5, 1.0));
  EXPECT_THROW(chol.factorize(grid_laplacian(5, 6, 1.0)), std::invalid_argument);
  EXPECT_THROW(chol.factorize(lower_from_dense(random_spd(25, 0.3, 1))), std::invalid_argument);
}

TEST(SparseCholesky, ValuesOnTheAnalysedPatternFactorLikeTheMatrix) {
  const CscMatrix a = grid_laplacian(8, 6, 0.5);
  const CscMatrix b = grid_laplacian(8, 6, 3.0);  // same pattern, other values
  SparseCholesky by_matrix, by_values;
  EXPECT_EQ(by_values.analyzed_pattern().rows, 0);
  EXPECT_THROW(by_values.factorize_values(b.values), std::logic_error);  // no analysis yet
  by_matrix.analyze(a);
  by_values.share_analysis(by_matrix);
  const CscMatrix& pattern = by_values.analyzed_pattern();
  EXPECT_EQ(pattern.rows, a.rows);
  EXPECT_EQ(pattern.cols, a.cols);
  EXPECT_EQ(pattern.col_start, a.col_start);
  EXPECT_EQ(pattern.row_index, a.row_index);
  EXPECT_TRUE(pattern.values.empty());
  by_matrix.factorize(b);
  by_values.factorize_values(b.values);
  const int nrhs = 3;
  const std::vector<double> rhs = random_values(static_cast<size_t>(a.rows) * nrhs, 8);
  std::vector<double> x = rhs, y = rhs;
  by_matrix.solve(x.data(), nrhs);
  by_values.solve(y.data(), nrhs);
  EXPECT_EQ(x, y);
  std::vector<double> short_values(b.values.begin(), b.values.end() - 1);
  EXPECT_THROW(by_values.factorize_values(short_values), std::invalid_argument);

  // A pattern without values is analysed as the matrix.
  CscMatrix pattern_only = a;
  pattern_only.values.clear();
  SparseCholesky by_pattern;
  by_pattern.analyze(pattern_only);
  EXPECT_EQ(by_pattern.permutation(), by_matrix.permutation());
  by_pattern.factorize_values(b.values);
  std::vector<double> z = rhs;
  by_pattern.solve(z.data(), nrhs);
  EXPECT_EQ(z, x);
  pattern_only.values.assign(3, 1.0);  // neither none nor one per entry
  EXPECT_THROW(by_pattern.analyze(pattern_only), std::invalid_argument);
}

TEST(SparseCholesky, InOrderHalvesMatchSolveAndGiveProductsWithTheInverse) {
  const CscMatrix a = grid_laplacian(23, 19, 0.1);
  SparseCholesky chol;
  chol.compute(a);
  const int n = a.rows;
  const int nrhs = 15;
  const int stride = SparseCholesky::padded_width(nrhs);
  ASSERT_GE(stride, nrhs);
  const std::vector<double> b = random_values(static_cast<size_t>(n) * nrhs, 41);
  std::vector<double> expected = b;
  chol.solve(expected.data(), nrhs);
  // b in the factor's row order, padded rows.
  const std::vector<int>& perm = chol.permutation();
  std::vector<double> x(static_cast<size_t>(n) * stride, 0.0);
  for (int row = 0; row < n; ++row)
    for (int c = 0; c < nrhs; ++c)
      x[static_cast<size_t>(row) * stride + c] = b[static_cast<size_t>(perm[row]) * nrhs + c];
  chol.forward_solve_in_order(x.data(), stride, nrhs);
  // b_0^T A^{-1} b_c from the forward half alone.
  for (int c = 0; c < nrhs; ++c) {
    double from_forward = 0.0, from_solve = 0.0;
    for (int row = 0; row < n; ++row) {
      from_forward += x[static_cast<size_t>(row) * stride] * x[static_cast<size_t>(row) * stride + c];
      from_solve += b[static_cast<size_t>(row) * nrhs] * expected[static_cast<size_t>(row) * nrhs + c];
    }
    EXPECT_NEAR(from_forward, from_solve, 1e-10 * (1.0 + std::abs(from_solve))) << "column " << c;
  }
  // The backward half on the first columns only: those equal solve(), the columns beyond its
  // whole vectors stay forward-solved.
  const std::vector<double> forward = x;
  chol.backward_solve_in_order(x.data(), stride, 3);
  const int touched = SparseCholesky::padded_width(3);
  for (int row = 0; row < n; ++row)
    for (int c = 0; c < nrhs; ++c) {
      const size_t at = static_cast<size_t>(row) * stride + c;
      if (c < 3)
        ASSERT_NEAR(x[at], expected[static_cast<size_t>(perm[row]) * nrhs + c], 1e-12 * (1 + std::abs(x[at])))
            << "row " << row << " column " << c;
      else if (c >= touched)
        ASSERT_EQ(x[at], forward[at]) << "row " << row << " column " << c;
    }
  EXPECT_THROW(chol.forward_solve_in_order(x.data(), stride + 1, nrhs), std::invalid_argument);
  EXPECT_THROW(chol.backward_solve_in_order(x.data(), stride, stride + 1), std::invalid_argument);
  SparseCholesky unfactored;
  EXPECT_THROW(unfactored.forward_solve_in_order(x.data(), stride, nrhs), std::logic_error);
}

TEST(SparseCholesky, InOrderSolvesGiveTheSameBitsOnAnyNumberOfThreads) {
  const CscMatrix a = grid_laplacian(31, 27, 0.1);
  SparseCholesky chol;
  chol.compute(a);
  // Several chunks of SIMD vectors of columns: the subtrees on the threads, each of their
  // supernodes taking every chunk in turn, then the vectors in groups over the top of the tree.
  const int nrhs = 40;
  const int stride = SparseCholesky::padded_width(nrhs);
  const std::vector<double> b = random_values(static_cast<size_t>(a.rows) * stride, 43);
  std::vector<double> serial = b;
  chol.forward_solve_in_order(serial.data(), stride, nrhs, 1);
  chol.backward_solve_in_order(serial.data(), stride, nrhs, 1);
  for (int threads : {2, 3, 0}) {
    std::vector<double> x = b;
    chol.forward_solve_in_order(x.data(), stride, nrhs, threads);
    chol.backward_solve_in_order(x.data(), stride, nrhs, threads);
    EXPECT_EQ(x, serial) << threads << " threads";
  }
}
