// SparseCholesky on MeshIK's own matrices: the normal matrix G'^T G' of the deformation
// gradients (4th-vertex unknowns kept and eliminated) of a generated sphere and of the real
// horse, the horse's graph Laplacian plus a shift, and the elephant's fill against AMD on a
// breadth-first numbering.
#include <amd.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "../../bench/normal_matrix.h"
#include "../../bench/obj_reader.h"
#include "../../bench/sphere_mesh.h"
#include "meshik/sparse_cholesky.h"
#include "sparse/breadth_first_order.h"
#include "sparse/symmetric_graph.h"
#include "sparse_test_matrices.h"

using meshik::CscMatrix;
using meshik::SparseCholesky;
using namespace meshik_test;

namespace {

// The rest mesh of a shared data folder (horse-poses, elephant-poses), or an empty mesh when it
// is absent.
meshik_bench::TriangleMesh rest_mesh_or_empty(const std::string& folder) {
  const char* env = std::getenv("MESHIK_SHARED_DATA");
  const std::string path = std::string(env ? env : "../shared/data") + "/" + folder + "/reference.obj";
  if (!std::filesystem::exists(path)) return {};
  return meshik_bench::read_obj(path);
}

meshik_bench::TriangleMesh horse_or_empty() { return rest_mesh_or_empty("horse-poses"); }

// Factors `a`, solves with 15 random right-hand sides; expects a small residual. Returns the
// solution (n by 15 row-major) for the right-hand sides `b`.
std::vector<double> solve_and_check(const CscMatrix& a, const std::vector<double>& b, int nrhs) {
  SparseCholesky chol;
  chol.compute(a);
  std::vector<double> x = b;
  chol.solve(x.data(), nrhs);
  EXPECT_LT(relative_residual(a, x, b, nrhs), 1e-10);
  return x;
}

// The kept form's vertex unknowns solve the eliminated form (its Schur complement) when the
// 4th-vertex right-hand sides are zero.
void expect_forms_agree(const meshik_bench::TriangleMesh& mesh, int handles) {
  const std::vector<int> h = meshik_bench::spread_handles(mesh.num_vertices(), handles);
  const CscMatrix kept = meshik_bench::deformation_normal_matrix(mesh, h, true);
  const CscMatrix eliminated = meshik_bench::deformation_normal_matrix(mesh, h, false);
  const int nrhs = 15, n = eliminated.rows;
  ASSERT_EQ(kept.rows, n + mesh.num_triangles());
  const std::vector<double> b = random_values(static_cast<size_t>(n) * nrhs, 42);
  std::vector<double> b_kept(static_cast<size_t>(kept.rows) * nrhs, 0.0);
  std::copy(b.begin(), b.end(), b_kept.begin());
  const std::vector<double> x = solve_and_check(eliminated, b, nrhs);
  const std::vector<double> x_kept = solve_and_check(kept, b_kept, nrhs);
  double scale = 0.0, worst = 0.0;
  for (size_t k = 0; k < x.size(); ++k) {
    scale = std::max(scale, std::abs(x[k]));
    worst = std::max(worst, std::abs(x[k] - x_kept[k]));
  }
  EXPECT_LT(worst, 1e-8 * scale);
}

}  // namespace

TEST(SparseCholeskyMesh, SphereNormalMatrixBothForms) {
  expect_forms_agree(meshik_bench::geodesic_sphere(8), 12);
}

TEST(SparseCholeskyMesh, FourthVerticesAddOnlyTheirOwnColumns) {
  const auto mesh = meshik_bench::geodesic_sphere(10);
  const std::vector<int> h = meshik_bench::spread_handles(mesh.num_vertices(), 16);
  SparseCholesky kept, eliminated;
  kept.analyze(meshik_bench::deformation_normal_matrix(mesh, h, true));
  eliminated.analyze(meshik_bench::deformation_normal_matrix(mesh, h, false));
  // Each 4th vertex adds its own column to L (diagonal + its free corners) and no fill.
  long long own_columns = 0;
  for (int c : mesh.triangles) own_columns += std::find(h.begin(), h.end(), c) == h.end();
  own_columns += mesh.num_triangles();
  EXPECT_EQ(kept.factor_nonzeros(), eliminated.factor_nonzeros() + own_columns);
}

TEST(SparseCholeskyMesh, HorseNormalMatrixBothForms) {
  const auto horse = horse_or_empty();
  if (horse.num_vertices() == 0) GTEST_SKIP() << "shared data (horse-poses/reference.obj) not found";
  expect_forms_agree(horse, 20);
}

// MeshIK analyses the mesh's system once and factors every handle set's on that pattern: the
// handles' rows and columns become identity ones. The free rows of the solution are those of
// the matrix with the handles removed.
TEST(SparseCholeskyMesh, HorseHandleSetsShareTheMeshAnalysis) {
  const auto horse = horse_or_empty();
  if (horse.num_vertices() == 0) GTEST_SKIP() << "shared data (horse-poses/reference.obj) not found";
  const CscMatrix mesh = meshik_bench::deformation_normal_matrix(horse, {}, false);
  SparseCholesky analysed;
  analysed.analyze(mesh);
  const int n = mesh.rows, nrhs = 15;
  for (int handles : {1, 16, 200}) {
    const std::vector<int> h = meshik_bench::spread_handles(n, handles);
    std::vector<int> column_of_vertex(n, 0);  // in the handle-free matrix, or -1
    for (int v : h) column_of_vertex[v] = -1;
    int columns = 0;
    for (int& c : column_of_vertex)
      if (c == 0) c = columns++;
    CscMatrix with_identity = mesh;
    for (int col = 0; col < n; ++col)
      for (int s = mesh.col_start[col]; s < mesh.col_start[col + 1]; ++s) {
        const int row = mesh.row_index[s];
        if (column_of_vertex[row] < 0 || column_of_vertex[col] < 0) with_identity.values[s] = row == col ? 1.0 : 0.0;
      }
    SparseCholesky shared;
    shared.share_analysis(analysed);
    shared.factorize(with_identity);
    const CscMatrix reduced = meshik_bench::deformation_normal_matrix(horse, h, false);
    const std::vector<double> b = random_values(static_cast<size_t>(columns) * nrhs, 11);
    const std::vector<double> x = solve_and_check(reduced, b, nrhs);
    std::vector<double> y(static_cast<size_t>(n) * nrhs, 0.0);
    for (int v = 0; v < n; ++v)
      if (column_of_vertex[v] >= 0)
        for (int c = 0; c < nrhs; ++c) y[static_cast<size_t>(v) * nrhs + c] = b[static_cast<size_t>(column_of_vertex[v]) * nrhs + c];
    shared.solve(y.data(), nrhs);
    double scale = 0.0, worst = 0.0;
    for (int v = 0; v < n; ++v)
      for (int c = 0; c < nrhs; ++c) {
        const double got = y[static_cast<size_t>(v) * nrhs + c];
        if (column_of_vertex[v] < 0) {
          ASSERT_EQ(got, 0.0) << "handle row " << v;
          continue;
        }
        const double expected = x[static_cast<size_t>(column_of_vertex[v]) * nrhs + c];
        scale = std::max(scale, std::abs(expected));
        worst = std::max(worst, std::abs(got - expected));
      }
    EXPECT_LT(worst, 1e-9 * scale) << handles << " handles";
  }
}

// The backward half asked for a few rows: those equal the full backward half's, and rows off
// their tree paths keep their values. The sphere's kept form starts with a simplicial prefix
// (its 4th vertices, among the asked rows); the grid and a random matrix have none.
TEST(SparseCholeskyMesh, BackwardHalfOnChosenRowsMatchesTheFullOne) {
  const auto sphere = meshik_bench::geodesic_sphere(8);
  const std::vector<int> handles = meshik_bench::spread_handles(sphere.num_vertices(), 12);
  for (const CscMatrix& a : {meshik_bench::deformation_normal_matrix(sphere, handles, true),
                             grid_laplacian(31, 27, 0.1), lower_from_dense(random_spd(40, 0.1, 7))}) {
    SparseCholesky chol;
    chol.compute(a);
    const int n = a.rows, nrhs = 5, stride = SparseCholesky::padded_width(nrhs);
    std::vector<double> full = random_values(static_cast<size_t>(n) * stride, 12);
    chol.forward_solve_in_order(full.data(), stride, nrhs);
    std::vector<double> chosen = full;
    const std::vector<int> rows = {n / 7, n / 3, n / 3 + 1, n - 2};
    chol.backward_solve_rows_in_order(chosen.data(), stride, nrhs, rows);
    const std::vector<double> forward = full;
    chol.backward_solve_in_order(full.data(), stride, nrhs);
    int kept = 0;  // rows off the paths
    for (int r = 0; r < n; ++r) {
      const bool asked = std::find(rows.begin(), rows.end(), r) != rows.end();
      bool unchanged = true;
      for (int c = 0; c < nrhs; ++c) {
        const size_t at = static_cast<size_t>(r) * stride + c;
        if (asked) ASSERT_NEAR(chosen[at], full[at], 1e-12 * (1.0 + std::abs(full[at]))) << "row " << r;
        unchanged = unchanged && chosen[at] == forward[at];
      }
      if (unchanged) ++kept;
    }
    if (n > 100) EXPECT_GT(kept, n / 2) << "the paths should be a small part of a mesh's factor";
    EXPECT_THROW(chol.backward_solve_rows_in_order(chosen.data(), stride, nrhs, {n}), std::invalid_argument);
  }
}

TEST(SparseCholeskyMesh, InOrderSolvesGiveTheSameBitsOnAnyNumberOfThreads) {
  // A mesh's factor: the backward half runs its elimination tree's subtrees on the threads.
  const auto sphere = meshik_bench::geodesic_sphere(16);
  const CscMatrix a =
      meshik_bench::deformation_normal_matrix(sphere, meshik_bench::spread_handles(sphere.num_vertices(), 12), false);
  SparseCholesky chol;
  chol.compute(a);
  const int n = a.rows;
  const std::vector<int> rows = {n / 5, n / 2, n - 3};
  for (int nrhs : {3, 15}) {
    const int stride = SparseCholesky::padded_width(nrhs);
    const std::vector<double> b = random_values(static_cast<size_t>(n) * stride, 44);
    std::vector<double> serial = b, serial_rows = b;
    chol.forward_solve_in_order(serial.data(), stride, nrhs, 1);
    serial_rows = serial;
    chol.backward_solve_in_order(serial.data(), stride, nrhs, 1);
    chol.backward_solve_rows_in_order(serial_rows.data(), stride, nrhs, rows, 1);
    for (int threads : {2, 3, 0}) {
      std::vector<double> x = b;
      chol.forward_solve_in_order(x.data(), stride, nrhs, threads);
      std::vector<double> x_rows = x;
      chol.backward_solve_in_order(x.data(), stride, nrhs, threads);
      chol.backward_solve_rows_in_order(x_rows.data(), stride, nrhs, rows, threads);
      EXPECT_EQ(x, serial) << nrhs << " columns, " << threads << " threads";
      EXPECT_EQ(x_rows, serial_rows) << nrhs << " columns, " << threads << " threads, chosen rows";
    }
  }
}

// Expects the factor of `a` on 2, 3 and all threads to give the serial factor's solution to the
// bit, and an indefinite copy of it (negative pivots in several places: the subtrees' and the
// top's columns) the serial error, naming the first failing pivot in the serial order.
void expect_same_bits_on_any_team(const CscMatrix& a) {
  const int n = a.rows, nrhs = 15;
  const std::vector<double> b = random_values(static_cast<size_t>(n) * nrhs, 45);
  SparseCholesky serial;
  serial.compute(a);
  std::vector<double> serial_x = b;
  serial.solve(serial_x.data(), nrhs);
  EXPECT_LT(relative_residual(a, serial_x, b, nrhs), 1e-10);
  CscMatrix indefinite = a;
  for (int column : {n / 7, n / 3, n / 2, n - 5})
    indefinite.values[indefinite.col_start[column]] = -1.0;  // the diagonal is a column's first entry
  std::string serial_error;
  try {
    serial.factorize(indefinite, 1);
  } catch (const meshik::NotPositiveDefinite& e) {
    serial_error = e.what();
  }
  ASSERT_FALSE(serial_error.empty());
  for (int threads : {2, 3, 0}) {
    SparseCholesky chol;
    chol.share_analysis(serial);
    chol.factorize(a, threads);
    std::vector<double> x = b;
    chol.solve(x.data(), nrhs);
    EXPECT_EQ(x, serial_x) << threads << " threads";
    try {
      chol.factorize(indefinite, threads);
      ADD_FAILURE() << "expected NotPositiveDefinite on " << threads << " threads";
    } catch (const meshik::NotPositiveDefinite& e) {
      EXPECT_EQ(std::string(e.what()), serial_error) << threads << " threads";
    }
  }
}

// The lower triangle of the 7-point Laplacian of an n by n by n grid plus I: separators of n^2
// columns, so the top of its elimination tree holds supernodes large enough for their dense
// kernels to be shared out over a team.
CscMatrix cube_laplacian(int n) {
  const auto index = [n](int x, int y, int z) { return (z * n + y) * n + x; };
  CscMatrix a;
  a.rows = a.cols = n * n * n;
  a.col_start.push_back(0);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        a.row_index.push_back(index(x, y, z));
        a.values.push_back(7.0);
        for (int below : {x + 1 < n ? index(x + 1, y, z) : -1, y + 1 < n ? index(x, y + 1, z) : -1,
                          z + 1 < n ? index(x, y, z + 1) : -1})
          if (below >= 0) {
            a.row_index.push_back(below);
            a.values.push_back(-1.0);
          }
        a.col_start.push_back(static_cast<int>(a.row_index.size()));
      }
  return a;
}

TEST(SparseCholeskyMesh, FactorizationGivesTheSameBitsOnAnyNumberOfThreads) {
  // A mesh's factor, its elimination tree split into several subtrees (SparseSubtreeSchedule's
  // test checks that split): each runs on a thread, then the top.
  const auto sphere = meshik_bench::geodesic_sphere(16);
  expect_same_bits_on_any_team(
      meshik_bench::deformation_normal_matrix(sphere, meshik_bench::spread_handles(sphere.num_vertices(), 12), false));
}

TEST(SparseCholeskyMesh, LargeTopSupernodesGiveTheSameBitsOnAnyNumberOfThreads) {
  // Node-level parallelism: a 3D grid (several subtrees, then a top of separators hundreds of
  // columns wide) and a dense matrix (one supernode, no subtrees: its kernels alone are shared).
  expect_same_bits_on_any_team(cube_laplacian(17));
  expect_same_bits_on_any_team(lower_from_dense(random_spd(1000, 1.0, 11)));
}

TEST(SparseCholeskyMesh, HorseShiftedGraphLaplacian) {
  const auto horse = horse_or_empty();
  if (horse.num_vertices() == 0) GTEST_SKIP() << "shared data (horse-poses/reference.obj) not found";
  // Lower triangle of L + 0.01 I for the horse's vertex graph.
  const int n = horse.num_vertices();
  std::vector<std::vector<int>> below(n);
  for (int t = 0; t < horse.num_triangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int u = horse.triangles[3 * t + c], v = horse.triangles[3 * t + (c + 1) % 3];
      below[std::min(u, v)].push_back(std::max(u, v));
    }
  CscMatrix a;
  a.rows = a.cols = n;
  a.col_start.push_back(0);
  std::vector<double> degree(n, 0.0);
  for (int j = 0; j < n; ++j) {
    std::sort(below[j].begin(), below[j].end());
    below[j].erase(std::unique(below[j].begin(), below[j].end()), below[j].end());
    for (int i : below[j]) degree[i] += 1.0, degree[j] += 1.0;
  }
  for (int j = 0; j < n; ++j) {
    a.row_index.push_back(j);
    a.values.push_back(degree[j] + 0.01);
    for (int i : below[j]) {
      a.row_index.push_back(i);
      a.values.push_back(-1.0);
    }
    a.col_start.push_back(static_cast<int>(a.row_index.size()));
  }
  const int nrhs = 16;
  solve_and_check(a, random_values(static_cast<size_t>(n) * nrhs, 9), nrhs);
}

// AMD's ties broken over the whole mesh (sparse/ordering.cpp): on the elephant's system the factor
// has fewer nonzeros than AMD's own order of the graph numbered breadth first (as the ExampleSet
// numbers its vertices), which the analysis gave before: 1.37M against 1.42M.
TEST(SparseCholeskyMesh, SpreadTieBreaksFillLessThanBreadthFirstNumbering) {
  const auto mesh = rest_mesh_or_empty("elephant-poses");
  if (mesh.num_vertices() == 0) GTEST_SKIP() << "shared data not found";
  const CscMatrix a =
      meshik_bench::deformation_normal_matrix(mesh, meshik_bench::spread_handles(mesh.num_vertices(), 16), false);
  const int n = a.rows;
  // The graph numbered breadth first, as sorted lists of the full symmetric pattern.
  const meshik::sparse::Pattern graph = meshik::sparse::adjacency_graph(a);
  const std::vector<int> breadth_first = meshik::sparse::breadth_first_order(graph.col_start, graph.row_index);
  std::vector<int> number(n);
  for (int t = 0; t < n; ++t) number[breadth_first[t]] = t;
  std::vector<int> numbered_start{0}, numbered;
  for (int t = 0; t < n; ++t) {
    std::vector<int> list;
    const int v = breadth_first[t];
    for (int p = graph.col_start[v]; p < graph.col_start[v + 1]; ++p) list.push_back(number[graph.row_index[p]]);
    list.push_back(t);
    std::sort(list.begin(), list.end());
    numbered.insert(numbered.end(), list.begin(), list.end());
    numbered_start.push_back(static_cast<int>(numbered.size()));
  }
  std::vector<int> perm(n);
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  ASSERT_EQ(amd_order(n, numbered_start.data(), numbered.data(), perm.data(), control, info), AMD_OK);
  const double breadth_first_nonzeros = info[AMD_LNZ] + n;  // AMD_LNZ leaves out the diagonal

  SparseCholesky chol;
  chol.analyze(a);
  EXPECT_LT(static_cast<double>(chol.factor_nonzeros()), 0.98 * breadth_first_nonzeros)
      << "breadth-first numbering gave " << breadth_first_nonzeros;
}
