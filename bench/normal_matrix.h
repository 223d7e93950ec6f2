// The MeshIK normal matrix G'^T G' of a triangle mesh, built here for the benchmarks and tests
// only (the product builds its own in cpp_core). G maps the unknown coordinates (one of x, y, z)
// of the vertices and of one extra "4th vertex" per triangle to the triangles' deformation
// gradients; G' drops the columns of the handle vertices.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <vector>

#include "meshik/sparse_cholesky.h"
#include "obj_reader.h"

namespace meshik_bench {

// Returns #handles vertex indices spread evenly over 0..num_vertices-1.
inline std::vector<int> spread_handles(int num_vertices, int handles) {
  std::vector<int> h;
  for (int k = 0; k < handles; ++k)
    h.push_back(static_cast<int>((static_cast<long long>(k) * num_vertices) / handles));
  return h;
}

// W = D V^{-1} (4 by 3) of triangle t: row k gives how corner k (v1, v2, v3, v4) enters the
// deformation gradient, where V = [v2-v1, v3-v1, v4-v1] and v4 = v1 + n / sqrt(|n|),
// n = (v2-v1) x (v3-v1).
inline Eigen::Matrix<double, 4, 3> gradient_weights(const TriangleMesh& mesh, int t) {
  Eigen::Vector3d p[3];
  for (int c = 0; c < 3; ++c)
    p[c] = Eigen::Vector3d::Map(&mesh.vertices[3 * mesh.triangles[3 * t + c]]);
  const Eigen::Vector3d e1 = p[1] - p[0], e2 = p[2] - p[0];
  const Eigen::Vector3d normal = e1.cross(e2);
  Eigen::Matrix3d v;
  v << e1, e2, normal / std::sqrt(normal.norm());
  const Eigen::Matrix3d v_inverse = v.inverse();
  Eigen::Matrix<double, 4, 3> w;
  w.row(0) = -v_inverse.colwise().sum();
  w.bottomRows<3>() = v_inverse;
  return w;
}

// The lower triangle of G'^T G' as a compressed-column matrix.
//   mesh:    #V vertices, #F triangles
//   handles: vertex indices whose columns are removed
//   keep_fourth_vertices: true gives the (#V - #handles + #F) square matrix with the 4th-vertex
//     unknowns last; false eliminates them exactly (their block is diagonal), giving the
//     (#V - #handles) square Schur complement with the sparsity of the mesh's vertex graph.
inline meshik::CscMatrix deformation_normal_matrix(const TriangleMesh& mesh,
                                                   const std::vector<int>& handles,
                                                   bool keep_fourth_vertices) {
  std::vector<int> unknown(mesh.num_vertices(), 0);
  for (int h : handles) unknown[h] = -1;
  int free_vertices = 0;
  for (int& u : unknown)
    if (u == 0) u = free_vertices++;
  const int n = free_vertices + (keep_fourth_vertices ? mesh.num_triangles() : 0);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(mesh.num_triangles()) * 10);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Matrix<double, 4, 3> w = gradient_weights(mesh, t);
    Eigen::Matrix4d block = w * w.transpose();
    int index[4];
    for (int c = 0; c < 3; ++c) index[c] = unknown[mesh.triangles[3 * t + c]];
    index[3] = keep_fourth_vertices ? free_vertices + t : -1;
    if (!keep_fourth_vertices)  // Schur complement of the 4th vertex's diagonal entry
      block.topLeftCorner<3, 3>() -=
          block.topRightCorner<3, 1>() * block.bottomLeftCorner<1, 3>() / block(3, 3);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        if (index[r] >= 0 && index[c] >= 0 && index[r] >= index[c])
          entries.emplace_back(index[r], index[c], block(r, c));
  }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  meshik::CscMatrix a;
  a.rows = a.cols = n;
  a.col_start.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + n + 1);
  a.row_index.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
  a.values.assign(lower.valuePtr(), lower.valuePtr() + lower.nonZeros());
  return a;
}

}  // namespace meshik_bench
