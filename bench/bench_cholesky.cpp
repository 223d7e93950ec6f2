// Benchmark of MeshIK's sparse Cholesky against CHOLMOD (simplicial and supernodal) and Eigen's
// SimplicialLDLT (AMD) on the same matrices in the same run: the MeshIK normal matrix G'^T G'
// of the real horse and elephant (4th-vertex unknowns eliminated and kept) and of a generated
// geodesic sphere. Prints the median time of each phase (analysis, numeric factorization, a
// solve with 15 right-hand sides) and OUR / THEIRS ratios.
//
// Usage: bench_cholesky [--samples DIR] [--data DIR] [--reps N] [--handles H] [--rhs K]
//                       [--sphere FREQUENCY] [--only NAME]
#include <cholmod.h>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "meshik/sparse_cholesky.h"
#include "normal_matrix.h"
#include "obj_reader.h"
#include "sphere_mesh.h"

namespace {

using meshik::CscMatrix;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string data = "../shared/data";
  int reps = 7;
  int handles = 20;
  int rhs = 15;
  int sphere_frequency = 100;  // 200,000 triangles
  std::string only;
};

// Median over `reps` runs of `run` in milliseconds, after one untimed warm-up run; `prepare`
// runs untimed before each.
double median_ms(int reps, const std::function<void()>& prepare, const std::function<void()>& run) {
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
Eigen::SparseMatrix<double> full_matrix(const CscMatrix& a) {
  Eigen::Map<const Eigen::SparseMatrix<double>> lower(a.rows, a.cols, a.row_index.size(),
                                                      a.col_start.data(), a.row_index.data(),
                                                      a.values.data());
  Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  return full;
}

// max_r ||A x_r - b_r|| / ||b_r|| for column-major n by k X and B.
double residual(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b) {
  const Eigen::MatrixXd r = a * x - b;
  double worst = 0;
  for (int c = 0; c < b.cols(); ++c) worst = std::max(worst, r.col(c).norm() / b.col(c).norm());
  return worst;
}

Result bench_meshik(const CscMatrix& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& full,
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

Result bench_cholmod(const CscMatrix& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& full,
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

Result bench_eigen_ldlt(const CscMatrix& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& full,
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

void print_row(const Result& r) {
  std::printf("  %-30s %10.0f %9.2f %9.2f %9.2f %9.2f   %.1e\n", r.name.c_str(), r.nnz_l, r.analyze_ms,
              r.numeric_ms, r.analyze_ms + r.numeric_ms, r.solve_ms, r.residual);
}

void bench_matrix(const std::string& name, const CscMatrix& a, const Options& options) {
  if (!options.only.empty() && name.find(options.only) == std::string::npos) return;
  std::printf("\n%s: n = %d, nnz(lower A) = %zu, %d right-hand sides, median of %d\n", name.c_str(),
              a.rows, a.row_index.size(), options.rhs, options.reps);
  std::printf("  %-30s %10s %9s %9s %9s %9s   %s\n", "solver", "nnz(L)", "analyze", "numeric",
              "factor", "solve", "residual");
  const Eigen::SparseMatrix<double> full = full_matrix(a);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows, options.rhs);
  const Result ours = bench_meshik(a, b, full, options.reps);
  print_row(ours);
  std::vector<Result> theirs = {bench_cholmod(a, b, full, options.reps, false),
                                bench_cholmod(a, b, full, options.reps, true),
                                bench_eigen_ldlt(a, b, full, options.reps)};
  for (const Result& r : theirs) print_row(r);
  const auto fastest = std::min_element(theirs.begin(), theirs.end(), [](const Result& x, const Result& y) {
    return x.analyze_ms + x.numeric_ms < y.analyze_ms + y.numeric_ms;
  });
  const double our_factor = ours.analyze_ms + ours.numeric_ms;
  std::printf("  floor: factor %.2f ms <= fastest library (%s, %.2f ms): %s", our_factor, fastest->name.c_str(),
              fastest->analyze_ms + fastest->numeric_ms,
              our_factor <= fastest->analyze_ms + fastest->numeric_ms ? "yes" : "NO");
  if (name.find("elephant") != std::string::npos)  // the project's floor for the elephant
    std::printf("; <= 60 ms: %s", our_factor <= 60.0 ? "yes" : "NO");
  std::printf("\n");
  std::printf("  OUR/THEIRS (factor = analyze + numeric; below 1 means MeshIK is faster)\n");
  for (const Result& r : theirs)
    std::printf("    vs %-30s factor %.2f  numeric %.2f  analyze %.2f  solve %.2f\n", r.name.c_str(),
                (ours.analyze_ms + ours.numeric_ms) / (r.analyze_ms + r.numeric_ms),
                ours.numeric_ms / r.numeric_ms, ours.analyze_ms / r.analyze_ms, ours.solve_ms / r.solve_ms);
}

void bench_mesh(const std::string& name, const meshik_bench::TriangleMesh& mesh, const Options& options) {
  const std::vector<int> handles = meshik_bench::spread_handles(mesh.num_vertices(), options.handles);
  std::printf("\n== %s: %d vertices, %d triangles, %d handles\n", name.c_str(), mesh.num_vertices(),
              mesh.num_triangles(), options.handles);
  bench_matrix(name + ", 4th vertices eliminated", meshik_bench::deformation_normal_matrix(mesh, handles, false), options);
  bench_matrix(name + ", 4th vertices kept", meshik_bench::deformation_normal_matrix(mesh, handles, true), options);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--data") o.data = value;
    else if (key == "--reps") o.reps = std::max(1, std::stoi(value));
    else if (key == "--handles") o.handles = std::stoi(value);
    else if (key == "--rhs") o.rhs = std::stoi(value);
    else if (key == "--sphere") o.sphere_frequency = std::stoi(value);
    else if (key == "--only") o.only = value;
    else if (key != "--samples") std::fprintf(stderr, "ignoring unknown option %s\n", key.c_str());
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  std::printf("MeshIK sparse Cholesky vs CHOLMOD %d.%d.%d and Eigen %d.%d.%d, single thread, times in ms\n",
              CHOLMOD_MAIN_VERSION, CHOLMOD_SUB_VERSION, CHOLMOD_SUBSUB_VERSION, EIGEN_WORLD_VERSION,
              EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION);
  for (const char* folder : {"horse-poses", "elephant-poses"}) {
    const std::string path = options.data + "/" + folder + "/reference.obj";
    if (!std::filesystem::exists(path)) {
      std::printf("\n(skipping %s: %s not found)\n", folder, path.c_str());
      continue;
    }
    bench_mesh(folder, meshik_bench::read_obj(path), options);
  }
  if (options.sphere_frequency > 0)
    bench_mesh("sphere-" + std::to_string(20 * options.sphere_frequency * options.sphere_frequency),
               meshik_bench::geodesic_sphere(options.sphere_frequency), options);
  return 0;
}
