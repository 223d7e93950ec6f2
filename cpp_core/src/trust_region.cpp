// Trust-region subproblem by eigen-decomposition of the scaled model matrix.
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 reductions (built with
// -march=native); the values it names are always written first.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "trust_region.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace meshik {

namespace {

// The model matrix and gradient in scaled coordinates z = D delta, in the eigenbasis of the
// scaled matrix: eigenvalues (ascending), eigenvectors, and the gradient's coordinates.
struct ScaledModel {
  Eigen::VectorXd eigenvalues;
  Eigen::MatrixXd eigenvectors;
  Eigen::VectorXd gradient;
};

ScaledModel scaled_model(const Eigen::MatrixXd& h, const Eigen::VectorXd& g, const Eigen::VectorXd& scale) {
  const Eigen::VectorXd inverse = scale.cwiseInverse();
  const Eigen::MatrixXd scaled = inverse.asDiagonal() * h * inverse.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (scaled + scaled.transpose()));
  ScaledModel model;
  model.eigenvalues = eigen.eigenvalues();
  model.eigenvectors = eigen.eigenvectors();
  model.gradient = model.eigenvectors.transpose() * inverse.cwiseProduct(g);
  return model;
}

// |z(mu)| for z(mu) = (H~ + mu I)^{-1} g~ in the eigenbasis.
double shifted_length(const ScaledModel& m, double mu) {
  return (m.gradient.array() / (m.eigenvalues.array() + mu)).matrix().norm();
}

}  // namespace

Eigen::VectorXd trust_region_scale(const Eigen::MatrixXd& s) {
  const double largest = std::max(s.diagonal().maxCoeff(), 1e-300);
  return s.diagonal().cwiseMax(1e-12 * largest).cwiseSqrt();
}

TrustRegionStep trust_region_step(const Eigen::MatrixXd& h, const Eigen::VectorXd& g,
                                  const Eigen::VectorXd& scale, double radius) {
  const ScaledModel m = scaled_model(h, g, scale);
  const int k = static_cast<int>(g.size());
  const double lowest = k > 0 ? m.eigenvalues(0) : 0.0;
  const double tiny = 1e-14 * std::max(m.eigenvalues.cwiseAbs().maxCoeff(), 1e-300);
  TrustRegionStep step;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(k);  // in the eigenbasis
  if (lowest > tiny && shifted_length(m, 0.0) <= radius) {
    z = m.gradient.array() / m.eigenvalues.array();
  } else {
    step.on_boundary = true;
    // |z(mu)| = radius for mu > max(0, -lowest); |z(mu)| decreases with mu.
    const double low = std::max(0.0, -lowest) + tiny;
    if (shifted_length(m, low) < radius) {
      // Hard case: the gradient has (almost) no component along the lowest eigenvector; go to
      // the boundary along it.
      for (int i = 0; i < k; ++i)
        if (m.eigenvalues(i) + low > 2.0 * tiny) z(i) = m.gradient(i) / (m.eigenvalues(i) + low);
      z(0) += std::sqrt(std::max(radius * radius - z.squaredNorm(), 0.0));
    } else {
      double lo = low, hi = std::max(low, m.gradient.norm() / std::max(radius, 1e-300) - lowest) + tiny;
      while (shifted_length(m, hi) > radius) hi = 2.0 * hi + tiny;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (shifted_length(m, mid) > radius ? lo : hi) = mid;
      }
      z = m.gradient.array() / (m.eigenvalues.array() + hi);
    }
  }
  const Eigen::VectorXd scaled_step = m.eigenvectors * z;
  step.delta = scaled_step.cwiseQuotient(scale);
  step.scaled_length = scaled_step.norm();
  step.predicted = 2.0 * g.dot(step.delta) - step.delta.dot(h * step.delta);
  return step;
}

GaussNewtonModel gauss_newton_model(const Eigen::MatrixXd& s, const Eigen::VectorXd& g,
                                    const Eigen::VectorXd& scale) {
  const ScaledModel m = scaled_model(s, g, scale);
  const double cutoff = 1e-12 * std::max(m.eigenvalues.cwiseAbs().maxCoeff(), 1e-300);
  GaussNewtonModel model;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(m.eigenvalues.size());
  for (int i = 0; i < m.eigenvalues.size(); ++i)
    if (m.eigenvalues(i) > cutoff) {
      z(i) = m.gradient(i) / m.eigenvalues(i);
      model.decrease += m.gradient(i) * z(i);
    }
  model.scaled_length = z.norm();
  model.delta = (m.eigenvectors * z).cwiseQuotient(scale);
  return model;
}

double updated_radius(double radius, const TrustRegionStep& step, double decrease) {
  if (!(decrease >= 0.25 * step.predicted) || !(decrease > 0.0)) return 0.25 * step.scaled_length;
  if (decrease > 0.75 * step.predicted && step.on_boundary) return 2.0 * radius;
  return radius;
}

}  // namespace meshik
