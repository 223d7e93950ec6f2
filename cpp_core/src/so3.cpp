// SO(3) exponential, logarithm, left Jacobian and the proper polar decomposition.
#include "so3.h"

#include <algorithm>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace meshik {

namespace {

// The cross-product matrix [v]_x, with [v]_x u = v x u.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi) {
  const RodriguesCoefficients k = rodrigues_coefficients(phi.squaredNorm());
  const Eigen::Matrix3d p = cross_matrix(phi);
  return Eigen::Matrix3d::Identity() + k.a * p + k.b * p * p;
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& r) {
  // v = sin(theta) axis from the antisymmetric part; cos(theta) from the trace.
  const Eigen::Vector3d v(0.5 * (r(2, 1) - r(1, 2)), 0.5 * (r(0, 2) - r(2, 0)),
                          0.5 * (r(1, 0) - r(0, 1)));
  const double cos_theta = std::clamp(0.5 * (r.trace() - 1.0), -1.0, 1.0);
  const double sin_theta = v.norm();
  const double theta = std::atan2(sin_theta, cos_theta);
  if (cos_theta > -0.5) {
    // theta < 2 pi / 3: the antisymmetric part determines the axis well.
    const double t2 = theta * theta;
    // theta / sin(theta) has no cancellation; only theta -> 0 needs the series.
    const double theta_over_sin =
        t2 < 1e-6 ? 1.0 + t2 / 6.0 * (1.0 + 7.0 * t2 / 60.0) : theta / sin_theta;
    return theta_over_sin * v;
  }
  // Near pi: (R + R^T)/2 = cos(theta) I + (1 - cos(theta)) axis axis^T; read the axis from the
  // column with the largest diagonal entry and take its sign from the antisymmetric part.
  const Eigen::Matrix3d outer =
      (0.5 * (r + r.transpose()) - cos_theta * Eigen::Matrix3d::Identity()) / (1.0 - cos_theta);
  int column = 0;
  outer.diagonal().maxCoeff(&column);
  Eigen::Vector3d axis = outer.col(column) / std::sqrt(std::max(outer(column, column), 1e-300));
  axis.normalize();
  if (axis.dot(v) < 0.0) axis = -axis;
  return theta * axis;
}

Eigen::Vector3d so3_left_jacobian_times(const Eigen::Vector3d& phi, const Eigen::Vector3d& u) {
  const RodriguesCoefficients k = rodrigues_coefficients(phi.squaredNorm());
  const Eigen::Vector3d phi_u = phi.cross(u);
  return u + k.b * phi_u + k.c * phi.cross(phi_u);
}

PolarDecomposition polar_decomposition(const Eigen::Matrix3d& t) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(t, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  // Singular values are sorted decreasingly: flip the last one when U V^T is a reflection.
  Eigen::Vector3d sign(1.0, 1.0, (u * v.transpose()).determinant() < 0.0 ? -1.0 : 1.0);
  PolarDecomposition polar;
  polar.rotation = u * sign.asDiagonal() * v.transpose();
  polar.stretch = v * (sign.cwiseProduct(svd.singularValues())).asDiagonal() * v.transpose();
  return polar;
}

}  // namespace meshik
