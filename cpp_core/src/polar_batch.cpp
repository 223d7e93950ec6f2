// Batched Newton polar decomposition and rotation logarithm (polar_batch.h).
#include "polar_batch.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "simd_clones.h"
#include "so3.h"

namespace meshik {

namespace {

constexpr int N = kPolarLanes;
// Newton steps before a lane is handed to the SVD (condition numbers up to ~1e12 converge in 20).
constexpr int kMaxSteps = 24;
// A step smaller than this (Frobenius norm) leaves the iterate within ~1e-16 of the limit
// (the error squares each step), so the iteration stops when every lane's step is below it.
constexpr double kConvergedStep = 1e-9;
// Scaling helps only far from convergence; near it, unscaled steps converge quadratically.
constexpr double kScaleWhileStepAbove = 1e-2;
// det(T) below this times |T|_F^3 (a near-degenerate or reflected matrix): SVD instead.
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

// One scaled Newton step on all lanes of x (9 rows of N lanes, row-major entries), in place;
// step_squared[l]: in, the square of lane l's previous step length (it decides the scaling);
// out, this one's. (Squares: no square root waits at the end of each step.)
MESHIK_LANE_INLINE void newton_step_lanes(double (&x)[9][N], double (&step_squared)[N]) {
  double c[9][N], det[N], half_g[N], half_inverse[N];
  // Cofactors: X^{-T} = C / det X.
  for (int l = 0; l < N; ++l) {
    c[0][l] = x[4][l] * x[8][l] - x[5][l] * x[7][l];
    c[1][l] = x[5][l] * x[6][l] - x[3][l] * x[8][l];
    c[2][l] = x[3][l] * x[7][l] - x[4][l] * x[6][l];
    c[3][l] = x[2][l] * x[7][l] - x[1][l] * x[8][l];
    c[4][l] = x[0][l] * x[8][l] - x[2][l] * x[6][l];
    c[5][l] = x[1][l] * x[6][l] - x[0][l] * x[7][l];
    c[6][l] = x[1][l] * x[5][l] - x[2][l] * x[4][l];
    c[7][l] = x[2][l] * x[3][l] - x[0][l] * x[5][l];
    c[8][l] = x[0][l] * x[4][l] - x[1][l] * x[3][l];
    det[l] = x[0][l] * c[0][l] + x[1][l] * c[1][l] + x[2][l] * c[2][l];
  }
  double norm_x[N] = {}, norm_c[N] = {};
  for (int e = 0; e < 9; ++e)
    for (int l = 0; l < N; ++l) {
      norm_x[l] += x[e][l] * x[e][l];
      norm_c[l] += c[e][l] * c[e][l];
    }
  // (omp simd: else the compiler unrolls this loop over lanes and leaves its divisions and
  // square roots scalar.)
#pragma omp simd
  for (int l = 0; l < N; ++l) {
    // g = sqrt(|X^{-1}|_F / |X|_F) = (|C|_F / (|det| |X|_F))^(1/2), only while far from converged.
    const double scaled = std::sqrt(std::sqrt(norm_c[l] / norm_x[l]) / std::abs(det[l]));
    const double g = step_squared[l] > kScaleWhileStepAbove * kScaleWhileStepAbove ? scaled : 1.0;
    half_g[l] = 0.5 * g;
    half_inverse[l] = 0.5 / (g * det[l]);
  }
  double change[N] = {};
  for (int e = 0; e < 9; ++e)
    for (int l = 0; l < N; ++l) {
      const double next = half_g[l] * x[e][l] + half_inverse[l] * c[e][l];
      change[l] += (next - x[e][l]) * (next - x[e][l]);
      x[e][l] = next;
    }
  for (int l = 0; l < N; ++l) step_squared[l] = change[l];
}

// Newton iteration on x (9 rows of N lanes), in place, until every lane's step is below
// kConvergedStep or kMaxSteps. Returns in converged[l] whether lane l got there.
MESHIK_LANE_INLINE void newton_polar_lanes(double (&x)[9][N], bool (&converged)[N]) {
  constexpr double kConvergedSquared = kConvergedStep * kConvergedStep;
  double step_squared[N];
  for (int l = 0; l < N; ++l) step_squared[l] = 1.0;
  for (int iteration = 0; iteration < kMaxSteps; ++iteration) {
    newton_step_lanes(x, step_squared);
    // Lanes still moving (a NaN step counts: !(NaN < bound)).
    double pending = 0.0;
#pragma omp simd reduction(+ : pending)
    for (int l = 0; l < N; ++l) pending += step_squared[l] < kConvergedSquared ? 0.0 : 1.0;
    if (pending == 0.0) break;
  }
  for (int l = 0; l < N; ++l) converged[l] = step_squared[l] < kConvergedSquared;
}

}  // namespace

MESHIK_SIMD_CLONES
void polar_and_log_batch(const double (&t)[9][kPolarLanes], int count, double (&rotation)[9][kPolarLanes],
                         double (&stretch)[9][kPolarLanes], double (&log)[3][kPolarLanes]) {
  // Lanes past count and lanes for the SVD iterate on the identity (converged at once). The
  // work goes on local arrays, which the compiler knows alias nothing (SIMD without checks).
  double m[9][N], x[9][N], sym[9][N], phi[3][N];
  std::memcpy(m, t, sizeof m);
  // det T - kMinRelativeDeterminant |T|_F^3 per lane: positive for the lanes Newton serves.
  // (Lane arrays of doubles, not bools: a bool among doubles keeps a loop from SIMD.)
  double margin[N], norm_squared[N] = {};
  for (int e = 0; e < 9; ++e)
    for (int l = 0; l < N; ++l) norm_squared[l] += m[e][l] * m[e][l];
  for (int l = 0; l < N; ++l) {
    const double det = m[0][l] * (m[4][l] * m[8][l] - m[5][l] * m[7][l]) +
                       m[1][l] * (m[5][l] * m[6][l] - m[3][l] * m[8][l]) +
                       m[2][l] * (m[3][l] * m[7][l] - m[4][l] * m[6][l]);
    const double norm = std::sqrt(norm_squared[l]);
    margin[l] = l < count ? det - kMinRelativeDeterminant * norm * norm * norm : -1.0;
  }
  for (int e = 0; e < 9; ++e)
    for (int l = 0; l < N; ++l) x[e][l] = margin[l] > 0.0 ? m[e][l] : (e % 4 == 0 ? 1.0 : 0.0);
  bool converged[N];
  newton_polar_lanes(x, converged);

  // S = sym(R^T T), and the logs for lanes whose angle is below 2 pi / 3 (v = sin(theta) axis,
  // see so3_log).
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < N; ++l) {
        const double rc = x[r][l] * m[c][l] + x[3 + r][l] * m[3 + c][l] + x[6 + r][l] * m[6 + c][l];
        const double cr = x[c][l] * m[r][l] + x[3 + c][l] * m[3 + r][l] + x[6 + c][l] * m[6 + r][l];
        sym[3 * r + c][l] = 0.5 * (rc + cr);
      }
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
  std::memcpy(stretch, sym, sizeof sym);
  std::memcpy(log, phi, sizeof phi);

  // The rare lanes the iteration does not serve: the SVD, and so3_log near a half turn.
  for (int l = 0; l < count; ++l) {
    const bool svd = !(margin[l] > 0.0) || !converged[l];
    if (!svd && cosine[l] > -0.5) continue;
    Eigen::Matrix3d r;
    for (int e = 0; e < 9; ++e) r(e / 3, e % 3) = rotation[e][l];
    if (svd) {
      Eigen::Matrix3d matrix;
      for (int e = 0; e < 9; ++e) matrix(e / 3, e % 3) = t[e][l];
      const PolarDecomposition polar = polar_decomposition(matrix);
      r = polar.rotation;
      for (int e = 0; e < 9; ++e) {
        rotation[e][l] = polar.rotation(e / 3, e % 3);
        stretch[e][l] = polar.stretch(e / 3, e % 3);
      }
    }
    const Eigen::Vector3d phi = so3_log(r);
    for (int d = 0; d < 3; ++d) log[d][l] = phi(d);
  }
}

}  // namespace meshik
