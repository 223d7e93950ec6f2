// Test matrices for the sparse Cholesky tests: random symmetric positive definite matrices,
// grid Laplacians, conversions between dense (Eigen) and lower-triangle CscMatrix, and
// symmetric products y = A x from the lower triangle.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "meshik/sparse_cholesky.h"

namespace meshik_test {

// Returns the lower triangle (row >= col) of the nonzeros of a dense n by n matrix; the
// diagonal is always stored.
inline meshik::CscMatrix lower_from_dense(const Eigen::MatrixXd& dense) {
  meshik::CscMatrix a;
  a.rows = a.cols = static_cast<int>(dense.rows());
  a.col_start.push_back(0);
  for (int j = 0; j < a.cols; ++j) {
    for (int i = j; i < a.rows; ++i)
      if (i == j || dense(i, j) != 0.0) {
        a.row_index.push_back(i);
        a.values.push_back(dense(i, j));
      }
    a.col_start.push_back(static_cast<int>(a.row_index.size()));
  }
  return a;
}

// Returns a random symmetric n by n matrix with off-diagonal density `density` (0..1), values in
// [-1, 1], made strictly diagonally dominant (hence positive definite).
inline Eigen::MatrixXd random_spd(int n, double density, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0), coin(0.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i)
      if (coin(rng) < density) a(i, j) = a(j, i) = value(rng);
  for (int i = 0; i < n; ++i) a(i, i) = a.row(i).cwiseAbs().sum() + 0.5 + coin(rng);
  return a;
}

// Returns the lower triangle of the 5-point Laplacian of an nx by ny grid plus shift * I
// (positive definite for shift > 0).
inline meshik::CscMatrix grid_laplacian(int nx, int ny, double shift) {
  meshik::CscMatrix a;
  a.rows = a.cols = nx * ny;
  a.col_start.push_back(0);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const int degree = (x > 0) + (x + 1 < nx) + (y > 0) + (y + 1 < ny);
      a.row_index.push_back(y * nx + x);
      a.values.push_back(degree + shift);
      if (x + 1 < nx) {
        a.row_index.push_back(y * nx + x + 1);
        a.values.push_back(-1.0);
      }
      if (y + 1 < ny) {
        a.row_index.push_back((y + 1) * nx + x);
        a.values.push_back(-1.0);
      }
      a.col_start.push_back(static_cast<int>(a.row_index.size()));
    }
  return a;
}

// y = A x for the symmetric A stored by its lower triangle `a`; x, y: n by nrhs row-major.
inline std::vector<double> symmetric_multiply(const meshik::CscMatrix& a,
                                              const std::vector<double>& x, int nrhs) {
  std::vector<double> y(x.size(), 0.0);
  for (int j = 0; j < a.cols; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i < j) continue;
      for (int r = 0; r < nrhs; ++r) {
        y[static_cast<size_t>(i) * nrhs + r] += a.values[p] * x[static_cast<size_t>(j) * nrhs + r];
        if (i != j)
          y[static_cast<size_t>(j) * nrhs + r] += a.values[p] * x[static_cast<size_t>(i) * nrhs + r];
      }
    }
  return y;
}

// Returns the largest over right-hand sides r of ||A x_r - b_r|| / ||b_r||; x, b n by nrhs
// row-major.
inline double relative_residual(const meshik::CscMatrix& a, const std::vector<double>& x,
                                const std::vector<double>& b, int nrhs) {
  const std::vector<double> ax = symmetric_multiply(a, x, nrhs);
  double worst = 0.0;
  for (int r = 0; r < nrhs; ++r) {
    double residual = 0.0, norm = 0.0;
    for (int i = 0; i < a.rows; ++i) {
      const size_t k = static_cast<size_t>(i) * nrhs + r;
      residual += (ax[k] - b[k]) * (ax[k] - b[k]);
      norm += b[k] * b[k];
    }
    worst = std::max(worst, std::sqrt(residual / norm));
  }
  return worst;
}

// Returns n * nrhs uniform random values in [-1, 1].
inline std::vector<double> random_values(size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> v(count);
  for (double& x : v) x = value(rng);
  return v;
}

}  // namespace meshik_test
