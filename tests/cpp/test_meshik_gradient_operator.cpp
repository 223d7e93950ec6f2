// The deformation-gradient operator G with the fourth vertices kept, and its exact elimination:
// T U equals the in-plane gradient of the corners, the eliminated matrix is the Schur complement
// of G^T G, and posing with the fourth vertices kept or eliminated gives the same vertices and
// the same energy; the pose system's handle coupling, read from K's lower triangle, is K's handle
// columns entry for entry.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include <Eigen/Dense>

#include "example_set_impl.h"
#include "gradient_operator.h"
#include "pose_system.h"
#include "test_meshik_support.h"
#include "triangle_frames.h"

namespace {

using meshik_test::ExampleMeshes;

// G (3 #F by #V + #F) as a dense matrix.
Eigen::MatrixXd dense_kept_operator(const ExampleMeshes& meshes, const meshik::TriangleFrames& frames) {
  const int n = meshes.num_vertices(), m = meshes.num_triangles();
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(3 * m, n + m);
  for (const meshik::MatrixEntry& e : meshik::kept_gradient_operator(frames, meshes.triangles.data(), n))
    g(e.row, e.col) += e.value;
  return g;
}

// K (#V by #V, every vertex used by a triangle) as a dense symmetric matrix, from its lower
// triangle's pattern and values.
Eigen::MatrixXd dense_eliminated_matrix(const std::vector<int>& triangles, const meshik::TriangleFrames& frames,
                                        int n) {
  std::vector<int> row_of_vertex(n);
  for (int v = 0; v < n; ++v) row_of_vertex[v] = v;
  const int m = static_cast<int>(triangles.size()) / 3;
  const meshik::CscMatrix pattern = meshik::eliminated_lower_pattern(triangles.data(), m, row_of_vertex, n);
  const std::vector<double> values =
      meshik::eliminated_lower_values(frames, triangles.data(), row_of_vertex, pattern);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int col = 0; col < n; ++col)
    for (int s = pattern.col_start[col]; s < pattern.col_start[col + 1]; ++s)
      k(pattern.row_index[s], col) = k(col, pattern.row_index[s]) = values[s];
  return k;
}

class GradientOperator : public ::testing::Test {
 protected:
  ExampleMeshes meshes_ = meshik_test::make_tube_examples();
  meshik::TriangleFrames frames_ =
      meshik::compute_triangle_frames(meshes_.rest.data(), meshes_.triangles.data(), meshes_.num_triangles());
};

TEST_F(GradientOperator, KeptOperatorGivesTheDeformationGradients) {
  const Eigen::MatrixXd g = dense_kept_operator(meshes_, frames_);
  const int n = meshes_.num_vertices(), m = meshes_.num_triangles();
  const std::vector<double>& pose = meshes_.examples[0];
  for (int c = 0; c < 3; ++c) {
    // Column c of the pose, followed by each triangle's deformed fourth vertex.
    Eigen::VectorXd x(n + m);
    for (int v = 0; v < n; ++v) x(v) = pose[3 * v + c];
    for (int j = 0; j < m; ++j) {
      const int* t = &meshes_.triangles[3 * j];
      const Eigen::Vector3d a = Eigen::Vector3d::Map(&pose[3 * t[0]]);
      x(n + j) = (a + meshik::fourth_vertex_offset(Eigen::Vector3d::Map(&pose[3 * t[1]]) - a,
                                                   Eigen::Vector3d::Map(&pose[3 * t[2]]) - a))(c);
    }
    const Eigen::VectorXd gradients = g * x;
    for (int j = 0; j < m; ++j) {
      const Eigen::Matrix3d t = meshik::deformation_gradient(frames_, meshes_.triangles.data(), pose.data(), j);
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(gradients(3 * j + r), t(c, r), 1e-12);
    }
  }
}

// A rotated, scaled and moved copy of the rest mesh: every triangle's edges and fourth vertex turn by
// the same s R, so each deformation gradient is s R, its column along the rest normal included (the
// inverse rest frame's last row, which the in-plane test below does not see).
TEST_F(GradientOperator, DeformationGradientOfASimilarCopyIsItsMatrix) {
  const Eigen::Matrix3d similarity =
      1.7 * Eigen::AngleAxisd(1.2, Eigen::Vector3d(0.3, -1.1, 0.6).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(0.4, -2.0, 1.5);
  std::vector<double> pose(meshes_.rest.size());
  for (int v = 0; v < meshes_.num_vertices(); ++v)
    Eigen::Vector3d::Map(&pose[3 * v]) = similarity * Eigen::Vector3d::Map(&meshes_.rest[3 * v]) + shift;
  for (int j = 0; j < meshes_.num_triangles(); ++j) {
    const Eigen::Matrix3d t = meshik::deformation_gradient(frames_, meshes_.triangles.data(), pose.data(), j);
    EXPECT_LT((t - similarity).norm(), 1e-12) << "triangle " << j << "\n" << t;
  }
}

TEST_F(GradientOperator, TimesThePlaneBasisItIsTheInPlaneGradientOfTheCorners) {
  std::mt19937 random(5);
  std::normal_distribution<double> normal;
  std::vector<double> pose(meshes_.rest.size());
  for (double& p : pose) p = normal(random);
  for (int j = 0; j < meshes_.num_triangles(); ++j) {
    const Eigen::Matrix<double, 3, 2> projected =
        meshik::deformation_gradient(frames_, meshes_.triangles.data(), pose.data(), j) *
        meshik::plane_basis_of(frames_, j);
    Eigen::Matrix<double, 3, 2> in_plane = Eigen::Matrix<double, 3, 2>::Zero();
    double g[6];
    meshik::corner_gradients(frames_.gradient.data() + meshik::kGradientEntries * j, g);
    for (int q = 0; q < 3; ++q)
      in_plane += Eigen::Vector3d::Map(&pose[3 * meshes_.triangles[3 * j + q]]) * Eigen::RowVector2d::Map(g + 2 * q);
    EXPECT_LT((projected - in_plane).norm(), 1e-11 * projected.norm()) << "triangle " << j;
  }
}

TEST_F(GradientOperator, EliminatedMatrixIsTheSchurComplementOfTheFourthVertices) {
  const int n = meshes_.num_vertices(), m = meshes_.num_triangles();
  const Eigen::MatrixXd g = dense_kept_operator(meshes_, frames_);
  const Eigen::MatrixXd a = g.transpose() * g;
  // The fourth-vertex block is diagonal: eliminating it is exact and cheap.
  const Eigen::MatrixXd fourth = a.bottomRightCorner(m, m);
  EXPECT_LT((fourth - Eigen::MatrixXd(fourth.diagonal().asDiagonal())).norm(), 1e-12 * fourth.norm());
  const Eigen::MatrixXd schur = a.topLeftCorner(n, n) - a.topRightCorner(n, m) *
                                                            fourth.diagonal().cwiseInverse().asDiagonal() *
                                                            a.bottomLeftCorner(m, n);
  const Eigen::MatrixXd dense_k = dense_eliminated_matrix(meshes_.triangles, frames_, n);
  EXPECT_LT((dense_k - schur).cwiseAbs().maxCoeff(), 1e-10 * schur.cwiseAbs().maxCoeff());
}

TEST_F(GradientOperator, KeptAndEliminatedFormsGiveTheSamePoseAndEnergy) {
  const int n = meshes_.num_vertices(), m = meshes_.num_triangles();
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes_.rest, 6);
  const std::vector<double> weights = {0.3, -0.2, 0.6};
  // Targets: the handles of a pose that is not the blend, so the energy is not zero.
  std::vector<double> targets = meshik_test::gather_rows(meshes_.examples[0], handles);
  for (double& t : targets) t *= 1.2;

  // Eliminated: the solver at fixed weights (linear space: T_j(w) = I + sum_i w_i (T_ij - I)),
  // features stored in double as the dense comparison computes them.
  const auto set = std::make_shared<meshik::ExampleSet>(meshes_.view(), meshes_.example_pointers(),
                                                        meshik::ProgressCallback{}, 0, meshik::FeaturePrecision::kDouble);
  meshik::SolverOptions options;
  options.feature_space = meshik::FeatureSpace::kLinear;
  options.max_iterations = 0;
  const meshik::SolveResult eliminated =
      meshik::Solver(set, handles, options).solve(targets.data(), weights.data());

  // Kept: least squares over the free vertices and all fourth vertices with the dense G.
  const Eigen::MatrixXd g = dense_kept_operator(meshes_, frames_);
  std::vector<int> handle_of(n, -1);
  for (size_t h = 0; h < handles.size(); ++h) handle_of[handles[h]] = static_cast<int>(h);
  std::vector<int> columns;
  for (int v = 0; v < n + m; ++v)
    if (v >= n || handle_of[v] < 0) columns.push_back(v);
  Eigen::MatrixXd g_free(3 * m, columns.size());
  for (size_t c = 0; c < columns.size(); ++c) g_free.col(c) = g.col(columns[c]);
  const Eigen::LDLT<Eigen::MatrixXd> normal(g_free.transpose() * g_free);
  double kept_energy = 0.0;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd rhs(3 * m);
    for (int j = 0; j < m; ++j) {
      Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
      for (size_t i = 0; i < weights.size(); ++i)
        t += weights[i] * (meshik::deformation_gradient(frames_, meshes_.triangles.data(),
                                                         meshes_.examples[i].data(), j) -
                           Eigen::Matrix3d::Identity());
      rhs.segment<3>(3 * j) = t.row(c).transpose();
    }
    for (size_t h = 0; h < handles.size(); ++h) rhs -= g.col(handles[h]) * targets[3 * h + c];
    const Eigen::VectorXd z = normal.solve(g_free.transpose() * rhs);
    kept_energy += (g_free * z - rhs).squaredNorm();
    for (size_t col = 0; col < columns.size(); ++col)
      if (columns[col] < n) EXPECT_NEAR(z(col), eliminated.vertices[3 * columns[col] + c], 1e-9);
  }
  EXPECT_NEAR(kept_energy, eliminated.residual, 1e-9 * kept_energy);
  EXPECT_GT(kept_energy, 1e-3);
}

TEST_F(GradientOperator, HandleCouplingIsTheMatrixsHandleColumns) {
  const meshik::ExampleSet set(meshes_.view(), meshes_.example_pointers());
  const meshik::ExampleSet::Impl& impl = set.impl();
  const int n = impl.num_vertices;
  // K on the internal vertices (all used by triangles here), both triangles.
  const Eigen::MatrixXd k = dense_eliminated_matrix(impl.triangles, impl.frames, n);
  std::vector<int> handles;
  for (int h : meshik_test::farthest_point_handles(meshes_.rest, 5)) handles.push_back(impl.internal_of_vertex[h]);
  const meshik::PoseSystem system(impl, handles);
  ASSERT_EQ(system.coupling_start().size(), handles.size() + 1);
  for (size_t h = 0; h < handles.size(); ++h) {
    // The handle's column of K on the free vertices (its neighbours in the mesh), in increasing
    // vertex order.
    std::vector<char> neighbour(n, 0);
    for (size_t c = 0; c < impl.triangles.size(); c += 3)
      for (int q = 0; q < 3; ++q)
        if (impl.triangles[c + q] == handles[h]) neighbour[impl.triangles[c + (q + 1) % 3]] =
                                                     neighbour[impl.triangles[c + (q + 2) % 3]] = 1;
    std::vector<int> rows;
    std::vector<double> values;
    for (int v = 0; v < n; ++v)
      if (neighbour[v] && system.unknown_of_vertex()[v] >= 0) {
        rows.push_back(system.unknown_of_vertex()[v]);
        values.push_back(k(v, handles[h]));
      }
    const auto begin = system.coupling_start()[h], end = system.coupling_start()[h + 1];
    EXPECT_EQ(std::vector<int>(system.coupling_row().begin() + begin, system.coupling_row().begin() + end), rows)
        << "handle " << h;
    EXPECT_EQ(std::vector<double>(system.coupling_value().begin() + begin, system.coupling_value().begin() + end),
              values)
        << "handle " << h;
    EXPECT_FALSE(rows.empty());
  }
}

}  // namespace
