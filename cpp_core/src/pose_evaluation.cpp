// The reduced energy, its optimal vertices and its Gauss-Newton system at given weights.
#include "pose_evaluation.h"

#include <algorithm>

#include "feature_space.h"

namespace meshik {

PoseEvaluator::PoseEvaluator(const ExampleSet::Impl& set, const PoseSystem& system,
                             FeatureSpace space, double regularization, const double* targets)
    : set_(set),
      system_(system),
      space_(space),
      regularization_(regularization),
      targets_(targets),
      coupling_(3 * static_cast<size_t>(system.num_unknowns())),
      handle_offset_(6 * system.handle_triangles().size(), 0.0),
      block_(blend_block_size(set.num_examples)),
      blended_(6 * static_cast<size_t>(set.num_triangles)) {
  const int k = set.num_examples;
  const size_t rhs_size = static_cast<size_t>(system.num_unknowns()) * 3 * (k + 1);
  rhs_.resize(rhs_size);
  rhs_before_solve_.resize(rhs_size);
  system.handle_coupling(targets, coupling_.data());
  // Handles' part of Q_j = sum over handle corners of target (x) g_q.
  const std::vector<int>& handle_of_vertex = system.handle_of_vertex();
  for (size_t slot = 0; slot < system.handle_triangles().size(); ++slot) {
    const int j = system.handle_triangles()[slot];
    const int* t = set.triangles.data() + 3 * j;
    const double* g = set.frames.gradient.data() + 6 * static_cast<size_t>(j);
    double* offset = handle_offset_.data() + 6 * slot;
    for (int q = 0; q < 3; ++q) {
      const int h = handle_of_vertex[t[q]];
      if (h < 0) continue;
      for (int c = 0; c < 3; ++c) {
        offset[2 * c] += targets[3 * h + c] * g[2 * q];
        offset[2 * c + 1] += targets[3 * h + c] * g[2 * q + 1];
      }
    }
  }
}

void PoseEvaluator::assemble(const double* weights, int columns, bool with_jacobian) {
  const int k = set_.num_examples;
  const int nrhs = 3 * columns;
  const int* triangles = set_.triangles.data();
  const std::vector<int>& unknown_of_vertex = system_.unknown_of_vertex();
  const std::vector<int>& slot_of_triangle = system_.handle_triangle_slot();
  std::fill(rhs_.begin(), rhs_.begin() + static_cast<size_t>(system_.num_unknowns()) * nrhs, 0.0);
  jtj_.setZero(k, k);
  jts_.setZero(k);
  double* block = block_.data();
  for (int j = 0; j < set_.num_triangles; ++j) {
    blend_triangle(set_.features, space_, weights, j, block);
    std::copy(block, block + 6, blended_.data() + 6 * static_cast<size_t>(j));
    if (with_jacobian) {
      double s[6];
      const int slot = slot_of_triangle[j];
      for (int e = 0; e < 6; ++e)
        s[e] = block[e] - (slot >= 0 ? handle_offset_[6 * static_cast<size_t>(slot) + e] : 0.0);
      for (int a = 0; a < k; ++a) {
        const double* ja = block + 6 * (a + 1);
        double dot_s = 0.0;
        for (int e = 0; e < 6; ++e) dot_s += ja[e] * s[e];
        jts_(a) += dot_s;
        for (int b = 0; b <= a; ++b) {
          const double* jb = block + 6 * (b + 1);
          double dot = 0.0;
          for (int e = 0; e < 6; ++e) dot += ja[e] * jb[e];
          jtj_(a, b) += dot;
        }
      }
    }
    // G'^T: each free corner q receives g_q . (row c of every block), for every coordinate c.
    const double* g = set_.frames.gradient.data() + 6 * static_cast<size_t>(j);
    for (int q = 0; q < 3; ++q) {
      const int u = unknown_of_vertex[triangles[3 * j + q]];
      if (u < 0) continue;
      const double g0 = g[2 * q], g1 = g[2 * q + 1];
      double* row = rhs_.data() + static_cast<size_t>(u) * nrhs;
      for (int c = 0; c < 3; ++c)
        for (int col = 0; col < columns; ++col)
          row[c * columns + col] += g0 * block[6 * col + 2 * c] + g1 * block[6 * col + 2 * c + 1];
    }
  }
  for (int u = 0; u < system_.num_unknowns(); ++u)
    for (int c = 0; c < 3; ++c) rhs_[static_cast<size_t>(u) * nrhs + c * columns] -= coupling_[3 * u + c];
  jtj_ = jtj_.selfadjointView<Eigen::Lower>();
}

void PoseEvaluator::gather_vertices(int columns, double* vertices) const {
  const std::vector<int>& unknown_of_vertex = system_.unknown_of_vertex();
  const std::vector<int>& handle_of_vertex = system_.handle_of_vertex();
  for (int v = 0; v < set_.num_vertices; ++v) {
    const double* from = set_.rest.data() + 3 * static_cast<size_t>(v);
    double solved[3];
    if (unknown_of_vertex[v] >= 0) {
      const double* row = rhs_.data() + static_cast<size_t>(unknown_of_vertex[v]) * 3 * columns;
      solved[0] = row[0];
      solved[1] = row[columns];
      solved[2] = row[2 * columns];
      from = solved;
    } else if (handle_of_vertex[v] >= 0) {
      from = targets_ + 3 * static_cast<size_t>(handle_of_vertex[v]);
    }
    std::copy(from, from + 3, vertices + 3 * static_cast<size_t>(v));
  }
}

double PoseEvaluator::residual_energy(const double* vertices) const {
  double energy = 0.0;
  for (int j = 0; j < set_.num_triangles; ++j) {
    const int* t = set_.triangles.data() + 3 * j;
    const double* g = set_.frames.gradient.data() + 6 * static_cast<size_t>(j);
    const double* f = blended_.data() + 6 * static_cast<size_t>(j);
    for (int c = 0; c < 3; ++c) {
      double r0 = -f[2 * c], r1 = -f[2 * c + 1];
      for (int q = 0; q < 3; ++q) {
        const double x = vertices[3 * static_cast<size_t>(t[q]) + c];
        r0 += x * g[2 * q];
        r1 += x * g[2 * q + 1];
      }
      energy += r0 * r0 + r1 * r1;
    }
  }
  return energy;
}

void PoseEvaluator::evaluate(const double* weights, bool with_jacobian, PoseEvaluation& out) {
  const int k = set_.num_examples;
  const int columns = with_jacobian ? k + 1 : 1;
  const int nrhs = 3 * columns;
  const int n_unknowns = system_.num_unknowns();
  assemble(weights, columns, with_jacobian);
  const size_t used = static_cast<size_t>(n_unknowns) * nrhs;
  if (with_jacobian) std::copy(rhs_.begin(), rhs_.begin() + used, rhs_before_solve_.begin());
  if (n_unknowns > 0) system_.solve(rhs_.data(), nrhs);

  out.weights.assign(weights, weights + k);
  out.vertices.resize(3 * static_cast<size_t>(set_.num_vertices));
  gather_vertices(columns, out.vertices.data());
  const Eigen::Map<const Eigen::VectorXd> w(weights, k);
  out.energy = residual_energy(out.vertices.data()) + regularization_ * w.squaredNorm();
  if (!with_jacobian) return;

  // H^T Z and H^T x0 over the three coordinates, H before and Z, x0 after the solve.
  Eigen::MatrixXd htz = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd htx = Eigen::VectorXd::Zero(k);
  for (int u = 0; u < n_unknowns; ++u) {
    for (int c = 0; c < 3; ++c) {
      const size_t base = static_cast<size_t>(u) * nrhs + c * columns;
      const double* h = rhs_before_solve_.data() + base + 1;
      const double* z = rhs_.data() + base + 1;
      const double x0 = rhs_[base];
      for (int a = 0; a < k; ++a) {
        htx(a) += h[a] * x0;
        for (int b = 0; b < k; ++b) htz(a, b) += h[a] * z[b];
      }
    }
  }
  out.schur = jtj_ - 0.5 * (htz + htz.transpose());
  out.schur.diagonal().array() += regularization_;
  out.step_rhs = htx - jts_ - regularization_ * w;
}

}  // namespace meshik
