// Element-wise math over small fixed-size arrays ("lanes"), written without calls or branches so
// that the compiler turns every loop into SIMD instructions: sine and cosine, and the Rodrigues
// coefficients of so3.h for a batch of rotation vectors.
#pragma once

namespace meshik {

// Rounds to the nearest integer (ties to even) for |v| < 2^51, without a library call.
inline double round_to_integer(double v) {
  constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
  return (v + kMagic) - kMagic;
}

// s[l] = sin(x[l]), c[l] = cos(x[l]) for 0 <= x[l] < 1e5, to within a few units in the last place.
// Cody-Waite reduction by pi/2 and the fdlibm kernel polynomials on [-pi/4, pi/4].
template <int kLanes>
inline void sin_cos_lanes(const double* x, double* s, double* c) {
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPiOver2Part1 = 1.57079632673412561417e+00;
  constexpr double kPiOver2Part2 = 6.07710050630396597660e-11;
  constexpr double kPiOver2Part3 = 2.02226624871116645580e-21;
  constexpr double kS1 = -1.66666666666666324348e-01, kS2 = 8.33333333332248946124e-03,
                   kS3 = -1.98412698298579493134e-04, kS4 = 2.75573137070700676789e-06,
                   kS5 = -2.50507602534068634195e-08, kS6 = 1.58969099521155010221e-10;
  constexpr double kC1 = 4.16666666666666019037e-02, kC2 = -1.38888888888741095749e-03,
                   kC3 = 2.48015872894767294178e-05, kC4 = -2.75573143513906633035e-07,
                   kC5 = 2.08757232129817482790e-09, kC6 = -1.13596475577881948265e-11;
  for (int l = 0; l < kLanes; ++l) {
    const double k = round_to_integer(x[l] * kTwoOverPi);
    const double r = ((x[l] - k * kPiOver2Part1) - k * kPiOver2Part2) - k * kPiOver2Part3;
    const double z = r * r;
    const double sine = r + r * z * (kS1 + z * (kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)))));
    const double cosine =
        1.0 - 0.5 * z + z * z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6)))));
    // Quadrant k mod 4 (k >= 0): floor(k / 4) is the integer nearest to k / 4 - 3/8.
    const double quadrant = k - 4.0 * round_to_integer(0.25 * k - 0.375);
    const bool odd = quadrant == 1.0 || quadrant == 3.0;
    const double sin_abs = odd ? cosine : sine;
    const double cos_abs = odd ? sine : cosine;
    s[l] = quadrant >= 2.0 ? -sin_abs : sin_abs;
    c[l] = (quadrant == 1.0 || quadrant == 2.0) ? -cos_abs : cos_abs;
  }
}

// 1 - x/d1 (1 - x/d2 (1 - x/d3 (1 - x/d4))) for constant d's, multiplying by their reciprocals
// (folded at compile time; a vector division costs about ten multiplications).
inline double nested_series(double x, double d1, double d2, double d3, double d4) {
  return 1.0 - x * (1.0 / d1) * (1.0 - x * (1.0 / d2) * (1.0 - x * (1.0 / d3) * (1.0 - x * (1.0 / d4))));
}

// For each lane, the Rodrigues coefficients of so3.h for |phi|^2 = theta_squared[l]:
// a = sin(t)/t, b = (1 - cos(t))/t^2, c = (t - sin(t))/t^3 (Taylor series below t = 0.1).
template <int kLanes>
inline void rodrigues_lanes(const double* theta_squared, double* a, double* b, double* c) {
  double theta[kLanes], half_sin[kLanes], half_cos[kLanes];
  for (int l = 0; l < kLanes; ++l) theta[l] = __builtin_sqrt(theta_squared[l] < 1e-2 ? 1e-2 : theta_squared[l]);
  double half[kLanes];
  for (int l = 0; l < kLanes; ++l) half[l] = 0.5 * theta[l];
  sin_cos_lanes<kLanes>(half, half_sin, half_cos);
  for (int l = 0; l < kLanes; ++l) {
    const double t2 = theta_squared[l];
    const double small_a = nested_series(t2, 6.0, 20.0, 42.0, 72.0);
    const double small_b = 0.5 * nested_series(t2, 12.0, 30.0, 56.0, 90.0);
    const double small_c = nested_series(t2, 20.0, 42.0, 72.0, 110.0) * (1.0 / 6.0);
    const double t = theta[l];
    const double sin_t = 2.0 * half_sin[l] * half_cos[l];
    const double inverse_t = 1.0 / t;
    const double inverse_t2 = inverse_t * inverse_t;
    const bool small = t2 < 1e-2;
    a[l] = small ? small_a : sin_t * inverse_t;
    b[l] = small ? small_b : 2.0 * half_sin[l] * half_sin[l] * inverse_t2;
    c[l] = small ? small_c : (t - sin_t) * inverse_t2 * inverse_t;
  }
}

// For each lane, the derivatives with respect to theta_squared of the coefficients b and c of
// rodrigues_lanes: db = (a - 2 b) / (2 t^2), dc = (b - 3 c) / (2 t^2) (Taylor series below
// t = 0.1). a, b, c: that function's output for the same theta_squared.
template <int kLanes>
inline void rodrigues_derivative_lanes(const double* theta_squared, const double* a, const double* b,
                                       const double* c, double* db, double* dc) {
  for (int l = 0; l < kLanes; ++l) {
    const double t2 = theta_squared[l];
    const double small_db =
        -1.0 / 24.0 + t2 * (1.0 / 360.0 - t2 * (1.0 / 13440.0 - t2 * (1.0 / 907200.0)));
    const double small_dc =
        -1.0 / 120.0 + t2 * (1.0 / 2520.0 - t2 * (1.0 / 120960.0 - t2 * (1.0 / 9979200.0)));
    const bool small = t2 < 1e-2;
    const double half_inverse = 0.5 / (small ? 1.0 : t2);
    db[l] = small ? small_db : (a[l] - 2.0 * b[l]) * half_inverse;
    dc[l] = small ? small_dc : (b[l] - 3.0 * c[l]) * half_inverse;
  }
}

}  // namespace meshik
