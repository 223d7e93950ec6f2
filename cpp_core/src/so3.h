// Rotations: the exponential and logarithm maps of SO(3), the left Jacobian of the exponential,
// and the polar decomposition of a 3x3 matrix into a proper rotation and a symmetric factor.
//
// A rotation vector phi = theta * axis stands for the rotation exp([phi]_x) by theta about axis.
// Every function is accurate for theta -> 0; the logarithm is also accurate near theta = pi.
#pragma once

#include <Eigen/Core>

#include "lane_math.h"

namespace meshik {

// The scalar coefficients of Rodrigues' formula for a rotation vector of length theta:
//   a = sin(theta) / theta, b = (1 - cos(theta)) / theta^2, c = (theta - sin(theta)) / theta^3.
// exp(phi) = I + a [phi]_x + b [phi]_x^2 and the left Jacobian J_l(phi) = I + b [phi]_x + c [phi]_x^2.
struct RodriguesCoefficients {
  double a = 1.0;
  double b = 0.5;
  double c = 1.0 / 6.0;
};

// Takes theta_squared = |phi|^2 >= 0; returns a, b, c to full double precision for every angle
// (Taylor series below theta = 0.1, half-angle sine and cosine above it; no cancellation).
inline RodriguesCoefficients rodrigues_coefficients(double theta_squared) {
  RodriguesCoefficients k;
  rodrigues_lanes<1>(&theta_squared, &k.a, &k.b, &k.c);
  return k;
}

// Rotation matrix of rotation vector phi (any length; not restricted to theta <= pi).
Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi);

// Principal logarithm of rotation matrix r (orthonormal, det +1): phi with |phi| <= pi and
// exp(phi) = r. At theta = pi exactly, either of the two opposite vectors is returned.
Eigen::Vector3d so3_log(const Eigen::Matrix3d& r);

// J_l(phi) u, the left Jacobian of exp applied to u:
//   d/dt exp(phi + t u) at t = 0 equals [J_l(phi) u]_x exp(phi).
Eigen::Vector3d so3_left_jacobian_times(const Eigen::Vector3d& phi, const Eigen::Vector3d& u);

// T = rotation * stretch with rotation a proper rotation (det +1) and stretch symmetric.
// When det T < 0 the stretch has one negative eigenvalue (along the direction of T's smallest
// singular value), so reflections and degenerate (rank-deficient) T are handled without failing.
struct PolarDecomposition {
  Eigen::Matrix3d rotation;
  Eigen::Matrix3d stretch;
};
PolarDecomposition polar_decomposition(const Eigen::Matrix3d& t);

}  // namespace meshik
