// MeshIK's sparse Cholesky and the libraries the benchmarks compare it with, on one matrix:
// CHOLMOD (simplicial and supernodal) and Eigen's SimplicialLDLT (AMD), each timed per phase
// (analysis, numeric factorization, a solve with the given right-hand sides). Shared by bench_cholesky,
// bench_scaling and bench_thread_scaling; the product never links these libraries.
#pragma once

#include <cholmod.h>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "meshik/sparse_cholesky.h"

namespace meshik_bench {

using meshik::CscMatrix;
using Clock = std::chrono::steady_clock;

// Median over `reps` runs of `run` in milliseconds, after one untimed warm-up run; `prepare`
// runs untimed before each.
inline double median_ms(int reps, const std::function<void()>& prepare, const std::function<void()>& run) {
  prepare();
  run();
  std::vector<double> ms;
  for (int r = 0; r < reps; ++r) {
    prepare();
    const auto start = Clock::now();
    run();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  std::nth_element(ms.begin(), ms.begin() + reps / 2, ms.end());
  return ms[reps / 2];
}

// One solver's results on one matrix.
struct Result {
  std::string name;
  double analyze_ms = 0, numeric_ms = 0, solve_ms = 0;
  double nnz_l = 0;
  double residual = 0;  // max over right-hand sides of ||A x - b|| / ||b||
};

// The symmetric matrix of the lower triangle `a` as an Eigen matrix (full storage).
inline Eigen::SparseMatrix<double> full_matrix(const CscMatrix& a) {
  Eigen::Map<const Eigen::SparseMatrix<double>> lower(a.rows, a.cols, a.row_index.size(),
                                                      a.col_start.data(), a.row_index.data(),
                                                      a.values.data());
  Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  return full;
}

// max_r ||A x_r - b_r|| / ||b_r|| for column-major n by k X and B.
inline double residual(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b) {
  const Eigen::MatrixXd r = a * x - b;
  double worst = 0;
  for (int c = 0; c < b.cols(); ++c) worst = std::max(worst, r.col(c).norm() / b.col(c).norm());
  return worst;
}

inline Result bench_cholmod(const CscMatrix& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& full,
                     int reps, bool supernodal) {
  Result r{supernodal ? "CHOLMOD supernodal" : "CHOLMOD simplicial"};
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  cholmod_sparse* ca = cholmod_allocate_sparse(a.rows, a.cols, a.row_index.size(), 1, 1, -1,
                                               CHOLMOD_REAL, &common);
  std::copy(a.col_start.begin(), a.col_start.end(), static_cast<int*>(ca->p));
  std::copy(a.row_index.begin(), a.row_index.end(), static_cast<int*>(ca->i));
  std::copy(a.values.begin(), a.values.end(), static_cast<double*>(ca->x));
  cholmod_factor* l = nullptr;
  r.analyze_ms = median_ms(reps, [&] { cholmod_free_factor(&l, &common); },
                           [&] { l = cholmod_analyze(ca, &common); });
  const int method = common.selected >= 0 ? common.method[common.selected].ordering : -1;
  r.name += method == CHOLMOD_METIS ? " (METIS)" : method == CHOLMOD_AMD ? " (AMD)" : "";
  r.numeric_ms = median_ms(reps, [] {}, [&] { cholmod_factorize(ca, l, &common); });
  if (common.status != CHOLMOD_OK) std::printf("  CHOLMOD status %d\n", common.status);
  r.nnz_l = common.lnz;
  cholmod_dense* cb = cholmod_allocate_dense(b.rows(), b.cols(), b.rows(), CHOLMOD_REAL, &common);
  std::copy(b.data(), b.data() + b.size(), static_cast<double*>(cb->x));
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
  r.solve_ms = median_ms(reps, [] {}, [&] { cholmod_solve2(CHOLMOD_A, l, cb, nullptr, &x, nullptr, &y, &e, &common); });
  r.residual = residual(full, Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(x->x), b.rows(), b.cols()), b);
  cholmod_free_dense(&x, &common);
  cholmod_free_dense(&y, &common);
  cholmod_free_dense(&e, &common);
  cholmod_free_dense(&cb, &common);
  cholmod_free_factor(&l, &common);
  cholmod_free_sparse(&ca, &common);
  cholmod_finish(&common);
  return r;
}

inline Result bench_eigen_ldlt(const CscMatrix& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& full,
                        int reps) {
  Result r{"Eigen SimplicialLDLT (AMD)"};
  Eigen::Map<const Eigen::SparseMatrix<double>> lower(a.rows, a.cols, a.row_index.size(),
                                                      a.col_start.data(), a.row_index.data(),
                                                      a.values.data());
  const Eigen::SparseMatrix<double> matrix = lower;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  r.analyze_ms = median_ms(reps, [] {}, [&] { ldlt.analyzePattern(matrix); });
  r.numeric_ms = median_ms(reps, [] {}, [&] { ldlt.factorize(matrix); });
  r.nnz_l = static_cast<double>(ldlt.matrixL().nestedExpression().nonZeros() + a.rows);
  Eigen::MatrixXd x;
  r.solve_ms = median_ms(reps, [] {}, [&] { x = ldlt.solve(b); });
  r.residual = residual(full, x, b);
  return r;
}

// MeshIK's own factorization, timed like the libraries.
inline Result bench_meshik(const CscMatrix& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& full,
                    int reps) {
  Result r{"MeshIK"};
  meshik::SparseCholesky chol;
  r.analyze_ms = median_ms(reps, [] {}, [&] { chol.analyze(a); });
  r.numeric_ms = median_ms(reps, [] {}, [&] { chol.factorize(a); });
  r.nnz_l = static_cast<double>(chol.factor_nonzeros());
  const int k = static_cast<int>(b.cols());
  // Our right-hand sides are row-major n by k.
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> b_rows = b;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x;
  r.solve_ms = median_ms(reps, [&] { x = b_rows; }, [&] { chol.solve(x.data(), k); });
  r.residual = residual(full, x, b);
  return r;
}

// The libraries of bench_libraries, in its order.
constexpr int kLibraries = 3;

// Library `index` (0 CHOLMOD simplicial, 1 CHOLMOD supernodal, 2 Eigen SimplicialLDLT) on the lower
// triangle a with right-hand sides b (n by k); full: a's symmetric matrix (full_matrix) for the
// residuals.
inline Result bench_library(int index, const CscMatrix& a, const Eigen::MatrixXd& b,
                            const Eigen::SparseMatrix<double>& full, int reps) {
  return index == 2 ? bench_eigen_ldlt(a, b, full, reps) : bench_cholmod(a, b, full, reps, index == 1);
}

// All kLibraries libraries (bench_library's arguments), in index order.
inline std::vector<Result> bench_libraries(const CscMatrix& a, const Eigen::MatrixXd& b,
                                           const Eigen::SparseMatrix<double>& full, int reps) {
  std::vector<Result> results;
  for (int index = 0; index < kLibraries; ++index) results.push_back(bench_library(index, a, b, full, reps));
  return results;
}

// The library whose factorization (analysis + numeric) was fastest (results: not empty).
inline std::vector<Result>::const_iterator fastest_factor(const std::vector<Result>& results) {
  return std::min_element(results.begin(), results.end(), [](const Result& x, const Result& y) {
    return x.analyze_ms + x.numeric_ms < y.analyze_ms + y.numeric_ms;
  });
}

// A library's factorization of the lower triangle `a` (analysis + numeric, one thread, medians of
// `reps` runs): its time, name and bench_library index (a plain struct, so a child process can send it).
struct LibraryFactor {
  double ms = 0;
  int index = 0;
  char name[64] = {};
};

// The LibraryFactor of results[index] (one of bench_libraries' results).
inline LibraryFactor library_factor_of(const std::vector<Result>& results, size_t index) {
  LibraryFactor out;
  out.ms = results[index].analyze_ms + results[index].numeric_ms;
  out.index = static_cast<int>(index);
  std::snprintf(out.name, sizeof out.name, "%s", results[index].name.c_str());
  return out;
}

// The fastest of the kLibraries libraries on `a` (15 random right-hand sides for their solves).
inline LibraryFactor fastest_library_factor(const CscMatrix& a, int reps) {
  const Eigen::SparseMatrix<double> full = full_matrix(a);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows, 15);
  const std::vector<Result> theirs = bench_libraries(a, b, full, reps);
  return library_factor_of(theirs, static_cast<size_t>(fastest_factor(theirs) - theirs.begin()));
}

// Library `index` alone on `a`, timed as fastest_library_factor times each library.
inline LibraryFactor one_library_factor(const CscMatrix& a, int index, int reps) {
  const Eigen::SparseMatrix<double> full = full_matrix(a);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows, 15);
  LibraryFactor out = library_factor_of({bench_library(index, a, b, full, reps)}, 0);
  out.index = index;
  return out;
}

}  // namespace meshik_bench
