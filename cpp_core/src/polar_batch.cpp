// Closed-form polar decompositions and rotation logs of triangles' deformation gradients
// (polar_batch.h).
#include "polar_batch.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "simd_clones.h"
#include "so3.h"

namespace meshik {

namespace {

constexpr int N = kPolarLanes;
// det(T) below this times |T|_F^3 (a nearly collapsed deformed triangle): SVD instead.
constexpr double kMinRelativeDeterminant = 1e-10;

// atan(t) for 0 <= t <= 1: reduced to |u| <= tan(pi/8) around 0 or pi/4, then fdlibm's odd
// polynomial (accurate to an ulp or two there).
MESHIK_LANE_INLINE double atan_unit(double t) {
  constexpr double kTanPiOver8 = 0.41421356237309504880;
  constexpr double kPiOver4 = 0.78539816339744830962;
  const bool reduce = t > kTanPiOver8;
  const double reduced = (t - 1.0) / (t + 1.0);  // both sides computed: a select, not a branch
  const double u = reduce ? reduced : t;
  const double z = u * u, w = z * z;
  const double s1 = z * (3.33333333333329318027e-01 +
                         w * (1.42857142725034663711e-01 +
                              w * (9.09088713343650656196e-02 +
                                   w * (6.66107313738753120669e-02 +
                                        w * (4.97687799461593236017e-02 + w * 1.62858201153657823623e-02)))));
  const double s2 = w * (-1.99999999998764832476e-01 +
                         w * (-1.11111104054623557880e-01 +
                              w * (-7.69187620504482999495e-02 +
                                   w * (-5.83357013379057348645e-02 + w * -3.65315727442169155270e-02))));
  const double p = u - u * (s1 + s2);
  return reduce ? kPiOver4 + p : p;
}

// atan2(s, c) for s >= 0 (not both zero).
MESHIK_LANE_INLINE double atan2_upper(double s, double c) {
  constexpr double kPiOver2 = 1.57079632679489661923, kPi = 3.14159265358979323846;
  const double a = std::abs(c);
  const bool steep = s > a;
  // One division of selected operands (a division under a condition keeps the loop from SIMD).
  const double t = (steep ? a : s) / (steep ? s : (a > 1e-300 ? a : 1e-300));
  double angle = atan_unit(t);
  angle = steep ? kPiOver2 - angle : angle;
  return c < 0.0 ? kPi - angle : angle;
}

// The lanes' closed-form factors (polar_batch.h) from the deformed edges e1, e2 and the rest
// triangles' E^{-1} rows (g: kGradientEntries rows) and plane bases: x (R, 9 rows), plane_stretch
// ((S - I) U, 6 rows) and margin: det T - kMinRelativeDeterminant |T|_F^3, not positive (or NaN)
// where the SVD must serve.
MESHIK_LANE_INLINE void closed_form_lanes(const double (&e1)[3][N], const double (&e2)[3][N],
                                          const double (&g)[kGradientEntries][N], const double* basis,
                                          double (&x)[9][N], double (&plane_stretch)[6][N], double (&margin)[N]) {
  for (int l = 0; l < N; ++l) {
    const double u1[3] = {basis[0 * N + l], basis[2 * N + l], basis[4 * N + l]};
    const double u2[3] = {basis[1 * N + l], basis[3 * N + l], basis[5 * N + l]};
    const double n[3] = {u1[1] * u2[2] - u1[2] * u2[1], u1[2] * u2[0] - u1[0] * u2[2], u1[0] * u2[1] - u1[1] * u2[0]};
    // The deformed frame: v1 along e1, m along e1 x e2, v2 = m x v1.
    const double c0 = e1[1][l] * e2[2][l] - e1[2][l] * e2[1][l];
    const double c1 = e1[2][l] * e2[0][l] - e1[0][l] * e2[2][l];
    const double c2 = e1[0][l] * e2[1][l] - e1[1][l] * e2[0][l];
    const double twice_area = std::sqrt(c0 * c0 + c1 * c1 + c2 * c2);
    const double length = std::sqrt(e1[0][l] * e1[0][l] + e1[1][l] * e1[1][l] + e1[2][l] * e1[2][l]);
    const double inverse_length = 1.0 / length, inverse_area = 1.0 / twice_area;
    const double v1[3] = {e1[0][l] * inverse_length, e1[1][l] * inverse_length, e1[2][l] * inverse_length};
    const double m[3] = {c0 * inverse_area, c1 * inverse_area, c2 * inverse_area};
    const double v2[3] = {m[1] * v1[2] - m[2] * v1[1], m[2] * v1[0] - m[0] * v1[2], m[0] * v1[1] - m[1] * v1[0]};
    // A = E~ E^{-1} = [a b; 0 d], E~ = [length q; 0 s], E^{-1} = [g0 g1; 0 g2].
    const double q = e2[0][l] * v1[0] + e2[1][l] * v1[1] + e2[2][l] * v1[2];
    const double s = e2[0][l] * v2[0] + e2[1][l] * v2[1] + e2[2][l] * v2[2];
    const double a = length * g[0][l], b = length * g[1][l] + q * g[2][l], d = s * g[2][l];
    // R2 = [cosine -sine; sine cosine] and P = R2^T A (symmetric).
    const double trace = a + d;
    const double inverse_r = 1.0 / std::sqrt(trace * trace + b * b);
    const double cosine = trace * inverse_r, sine = -b * inverse_r;
    const double p11 = a * trace * inverse_r, p12 = a * b * inverse_r, p22 = (b * b + trace * d) * inverse_r;
    // R = [w1 w2] U^T + m n^T with [w1 w2] = [v1 v2] R2; (S - I) U = U (P - I).
    for (int r = 0; r < 3; ++r) {
      const double w1 = cosine * v1[r] + sine * v2[r], w2 = cosine * v2[r] - sine * v1[r];
      for (int c = 0; c < 3; ++c) x[3 * r + c][l] = w1 * u1[c] + w2 * u2[c] + m[r] * n[c];
      plane_stretch[2 * r][l] = u1[r] * (p11 - 1.0) + u2[r] * p12;
      plane_stretch[2 * r + 1][l] = u1[r] * p12 + u2[r] * (p22 - 1.0);
    }
    // det T = a d sigma and |T|_F^2 = a^2 + b^2 + d^2 + sigma^2, with sigma^2 the ratio of the
    // areas (the rest triangle's twice area is 1 / (g0 g2)).
    const double sigma_squared = twice_area * g[0][l] * g[2][l];
    const double norm_squared = a * a + b * b + d * d + sigma_squared;
    margin[l] = a * d * std::sqrt(sigma_squared) - kMinRelativeDeterminant * norm_squared * std::sqrt(norm_squared);
  }
}

}  // namespace

MESHIK_SIMD_CLONES
void triangle_polar_and_log_batch(const TriangleFrames& frames, const double* plane_basis, const int* triangles,
                                  const double* vertices, int first, int count, double (&rotation)[9][kPolarLanes],
                                  double (&plane_stretch)[6][kPolarLanes], double (&log)[3][kPolarLanes]) {
  // The work goes on local arrays, which the compiler knows alias nothing (SIMD without checks).
  double e1[3][N], e2[3][N], g[kGradientEntries][N], x[9][N], stretch[6][N], margin[N], phi[3][N];
  const double* basis = plane_basis + 6 * N * static_cast<size_t>(first / N);
  edge_lanes(vertices, triangles, first, count, e1, e2);
  for (int l = 0; l < N; ++l) {
    const size_t j = static_cast<size_t>(first + (l < count ? l : count - 1));
    for (int e = 0; e < kGradientEntries; ++e) g[e][l] = frames.gradient[kGradientEntries * j + e];
  }
  closed_form_lanes(e1, e2, g, basis, x, stretch, margin);

  // The logs for lanes whose angle is below 2 pi / 3 (v = sin(theta) axis, see so3_log).
  double cosine[N];
  for (int l = 0; l < N; ++l) {
    const double v0 = 0.5 * (x[7][l] - x[5][l]), v1 = 0.5 * (x[2][l] - x[6][l]), v2 = 0.5 * (x[3][l] - x[1][l]);
    const double trace_term = 0.5 * (x[0][l] + x[4][l] + x[8][l] - 1.0);
    const double cos_theta = trace_term < -1.0 ? -1.0 : (trace_term > 1.0 ? 1.0 : trace_term);
    const double sin_theta = std::sqrt(v0 * v0 + v1 * v1 + v2 * v2);
    const double theta = atan2_upper(sin_theta, cos_theta);
    const double t2 = theta * theta;
    const double ratio = theta / (sin_theta > 1e-300 ? sin_theta : 1e-300);
    const double series = 1.0 + t2 / 6.0 * (1.0 + 7.0 * t2 / 60.0);
    const double theta_over_sin = t2 < 1e-6 ? series : ratio;
    phi[0][l] = theta_over_sin * v0;
    phi[1][l] = theta_over_sin * v1;
    phi[2][l] = theta_over_sin * v2;
    cosine[l] = cos_theta;  // (a bool written here would keep the loop from SIMD)
  }
  std::memcpy(rotation, x, sizeof x);
  std::memcpy(plane_stretch, stretch, sizeof stretch);
  std::memcpy(log, phi, sizeof phi);

  // The rare lanes the closed form does not serve: the SVD, and so3_log near a half turn.
  bool gradients_read = false;
  double t[9][N];
  for (int l = 0; l < count; ++l) {
    const bool svd = !(margin[l] > 0.0);
    if (!svd && cosine[l] > -0.5) continue;
    Eigen::Matrix3d r;
    for (int e = 0; e < 9; ++e) r(e / 3, e % 3) = rotation[e][l];
    if (svd) {
      if (!gradients_read)
        deformation_gradients(frames.gradient.data(), plane_basis, triangles, vertices, first, count, t);
      gradients_read = true;
      Eigen::Matrix3d matrix;
      for (int e = 0; e < 9; ++e) matrix(e / 3, e % 3) = t[e][l];
      const PolarDecomposition polar = polar_decomposition(matrix);
      r = polar.rotation;
      for (int e = 0; e < 9; ++e) rotation[e][l] = polar.rotation(e / 3, e % 3);
      for (int row = 0; row < 3; ++row)
        for (int c = 0; c < 2; ++c) {
          double sum = 0.0;
          for (int k = 0; k < 3; ++k)
            sum += (polar.stretch(row, k) - (k == row ? 1.0 : 0.0)) * basis[(2 * k + c) * N + l];
          plane_stretch[2 * row + c][l] = sum;
        }
    }
    const Eigen::Vector3d principal = so3_log(r);
    for (int d = 0; d < 3; ++d) log[d][l] = principal(d);
  }
}

}  // namespace meshik
