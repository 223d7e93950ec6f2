// Trust-region steps for the small (#E by #E) weight problem: minimise the quadratic model
//   m(delta) = -2 g.delta + delta^T H delta      (H symmetric, possibly indefinite)
// subject to |D delta| <= radius, by eigen-decomposition and a 1-D search for the shift mu with
// (H + mu D^2) delta = g (Moré-Sorensen, including the "hard case").
#pragma once

#include <Eigen/Core>

namespace meshik {

struct TrustRegionStep {
  Eigen::VectorXd delta;      // #E: the step
  double predicted = 0.0;     // model decrease 2 g.delta - delta^T H delta (>= 0)
  double scaled_length = 0.0; // |D delta|
  bool on_boundary = false;   // the radius restricted the step
};

// The scaling D of the trust region for Gauss-Newton matrix s (#E by #E): sqrt(diag s), floored
// at a small fraction of its largest entry.
Eigen::VectorXd trust_region_scale(const Eigen::MatrixXd& s);

// h: #E by #E model matrix; g: #E; scale: #E positive entries of the diagonal D; radius >= 0.
TrustRegionStep trust_region_step(const Eigen::MatrixXd& h, const Eigen::VectorXd& g,
                                  const Eigen::VectorXd& scale, double radius);

// The Gauss-Newton step s delta = g (s positive semi-definite; numerically zero eigenvalues are
// left out): its scaled length |D delta| (the first radius) and its model decrease g.delta (a
// measure of stationarity that does not depend on the radius).
struct GaussNewtonModel {
  Eigen::VectorXd delta;  // the step
  double scaled_length = 0.0;
  double decrease = 0.0;
};
GaussNewtonModel gauss_newton_model(const Eigen::MatrixXd& s, const Eigen::VectorXd& g,
                                    const Eigen::VectorXd& scale);

// The radius after `step` changed the energy by -decrease: a quarter of the step when the model
// predicted poorly (or the energy rose), doubled when it predicted well at the boundary.
double updated_radius(double radius, const TrustRegionStep& step, double decrease);

}  // namespace meshik
