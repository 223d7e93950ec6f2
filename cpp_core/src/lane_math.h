// Element-wise math over small fixed-size arrays ("lanes"), written without calls or branches so
// that the compiler turns every loop into SIMD instructions: sine and cosine, and the Rodrigues
// coefficients of so3.h for a batch of rotation vectors, in double or single precision (Real;
// every constant is a Real, so single-precision lanes never widen to double).
#pragma once

namespace meshik {

// Rounds to the nearest integer (ties to even) without a library call: for |v| < 2^51 in double,
// |v| < 2^22 in single precision (adding and subtracting 1.5 times 2^(mantissa bits)).
inline double round_to_integer(double v) {
  constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
  return (v + kMagic) - kMagic;
}
inline float round_to_integer(float v) {
  constexpr float kMagic = 12582912.0f;  // 1.5 * 2^23
  return (v + kMagic) - kMagic;
}

// Square root of v >= 0 at the lane's own precision (no widening of a float to double).
inline double lane_sqrt(double v) { return __builtin_sqrt(v); }
inline float lane_sqrt(float v) { return __builtin_sqrtf(v); }

// s[l] = sin(x[l]), c[l] = cos(x[l]) for 0 <= x[l] < 1e5 (double; 1e3 in single precision), to
// within a few units in the last place of Real. Cody-Waite reduction by pi/2 and the fdlibm
// kernel polynomials on [-pi/4, pi/4] (their double coefficients, rounded for float).
template <int kLanes, typename Real = double>
inline void sin_cos_lanes(const Real* x, Real* s, Real* c) {
  constexpr Real kTwoOverPi = Real(6.36619772367581382433e-01);
  constexpr Real kPiOver2Part1 = Real(1.57079632673412561417e+00);
  constexpr Real kPiOver2Part2 = Real(6.07710050630396597660e-11);
  constexpr Real kPiOver2Part3 = Real(2.02226624871116645580e-21);
  constexpr Real kS1 = Real(-1.66666666666666324348e-01), kS2 = Real(8.33333333332248946124e-03),
                 kS3 = Real(-1.98412698298579493134e-04), kS4 = Real(2.75573137070700676789e-06),
                 kS5 = Real(-2.50507602534068634195e-08), kS6 = Real(1.58969099521155010221e-10);
  constexpr Real kC1 = Real(4.16666666666666019037e-02), kC2 = Real(-1.38888888888741095749e-03),
                 kC3 = Real(2.48015872894767294178e-05), kC4 = Real(-2.75573143513906633035e-07),
                 kC5 = Real(2.08757232129817482790e-09), kC6 = Real(-1.13596475577881948265e-11);
  constexpr Real kOne = 1, kTwo = 2, kThree = 3, kFour = 4, kHalf = Real(0.5), kQuarter = Real(0.25),
                 kThreeEighths = Real(0.375);
  for (int l = 0; l < kLanes; ++l) {
    const Real k = round_to_integer(x[l] * kTwoOverPi);
    const Real r = ((x[l] - k * kPiOver2Part1) - k * kPiOver2Part2) - k * kPiOver2Part3;
    const Real z = r * r;
    const Real sine = r + r * z * (kS1 + z * (kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)))));
    const Real cosine =
        kOne - kHalf * z + z * z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6)))));
    // Quadrant k mod 4 (k >= 0): floor(k / 4) is the integer nearest to k / 4 - 3/8.
    const Real quadrant = k - kFour * round_to_integer(kQuarter * k - kThreeEighths);
    const bool odd = quadrant == kOne || quadrant == kThree;
    const Real sin_abs = odd ? cosine : sine;
    const Real cos_abs = odd ? sine : cosine;
    s[l] = quadrant >= kTwo ? -sin_abs : sin_abs;
    c[l] = (quadrant == kOne || quadrant == kTwo) ? -cos_abs : cos_abs;
  }
}

// 1 - x/d1 (1 - x/d2 (1 - x/d3 (1 - x/d4))) for constant d's, multiplying by their reciprocals
// (folded at compile time; a vector division costs about ten multiplications).
template <typename Real>
inline Real nested_series(Real x, double d1, double d2, double d3, double d4) {
  const Real one = 1;
  return one - x * Real(1.0 / d1) *
                   (one - x * Real(1.0 / d2) * (one - x * Real(1.0 / d3) * (one - x * Real(1.0 / d4))));
}

// theta^2 below which the Rodrigues coefficients come from their Taylor series: t = 0.1 in
// double; t = 1 in single precision, where the closed forms' cancellation (t - sin t, and
// b - 3 c in dc) would cost most of a float's digits below 1, while the series stay exact to
// float precision up to t = 1 (their next terms are below 3e-8 of the sum there).
template <typename Real>
constexpr Real kRodriguesSeriesBelow = sizeof(Real) < sizeof(double) ? Real(1) : Real(1e-2);

// For each lane, the Rodrigues coefficients of so3.h for |phi|^2 = theta_squared[l]:
// a = sin(t)/t, b = (1 - cos(t))/t^2, c = (t - sin(t))/t^3 (Taylor series below the above).
template <int kLanes, typename Real = double>
inline void rodrigues_lanes(const Real* theta_squared, Real* a, Real* b, Real* c) {
  constexpr Real kSeriesBelow = kRodriguesSeriesBelow<Real>, kHalf = Real(0.5), kOne = 1, kTwo = 2, kSixth = Real(1.0 / 6.0);
  // theta is used by the closed forms alone, which the series replace below kSeriesBelow: there
  // it may be 0 and the closed forms infinite or NaN, never selected. Unclamped, the square root
  // stays one vector instruction (a clamp let the compiler branch around it, lane by lane).
  Real theta[kLanes], half_sin[kLanes], half_cos[kLanes];
  for (int l = 0; l < kLanes; ++l) theta[l] = lane_sqrt(theta_squared[l]);
  Real half[kLanes];
  for (int l = 0; l < kLanes; ++l) half[l] = kHalf * theta[l];
  sin_cos_lanes<kLanes>(half, half_sin, half_cos);
  for (int l = 0; l < kLanes; ++l) {
    const Real t2 = theta_squared[l];
    const Real small_a = nested_series(t2, 6.0, 20.0, 42.0, 72.0);
    const Real small_b = kHalf * nested_series(t2, 12.0, 30.0, 56.0, 90.0);
    const Real small_c = nested_series(t2, 20.0, 42.0, 72.0, 110.0) * kSixth;
    const Real t = theta[l];
    const Real sin_t = kTwo * half_sin[l] * half_cos[l];
    const Real inverse_t = kOne / t;
    const Real inverse_t2 = inverse_t * inverse_t;
    const bool small = t2 < kSeriesBelow;
    a[l] = small ? small_a : sin_t * inverse_t;
    b[l] = small ? small_b : kTwo * half_sin[l] * half_sin[l] * inverse_t2;
    c[l] = small ? small_c : (t - sin_t) * inverse_t2 * inverse_t;
  }
}

// For each lane, the derivatives with respect to theta_squared of the coefficients b and c of
// rodrigues_lanes: db = (a - 2 b) / (2 t^2), dc = (b - 3 c) / (2 t^2) (Taylor series below
// kRodriguesSeriesBelow). a, b, c: that function's output for the same theta_squared.
template <int kLanes, typename Real = double>
inline void rodrigues_derivative_lanes(const Real* theta_squared, const Real* a, const Real* b, const Real* c,
                                       Real* db, Real* dc) {
  constexpr Real kSeriesBelow = kRodriguesSeriesBelow<Real>, kHalf = Real(0.5), kOne = 1, kTwo = 2, kThree = 3;
  for (int l = 0; l < kLanes; ++l) {
    const Real t2 = theta_squared[l];
    const Real small_db = Real(-1.0 / 24.0) +
                          t2 * (Real(1.0 / 360.0) - t2 * (Real(1.0 / 13440.0) - t2 * Real(1.0 / 907200.0)));
    const Real small_dc = Real(-1.0 / 120.0) +
                          t2 * (Real(1.0 / 2520.0) - t2 * (Real(1.0 / 120960.0) - t2 * Real(1.0 / 9979200.0)));
    const bool small = t2 < kSeriesBelow;
    const Real half_inverse = kHalf / (small ? kOne : t2);
    db[l] = small ? small_db : (a[l] - kTwo * b[l]) * half_inverse;
    dc[l] = small ? small_dc : (b[l] - kThree * c[l]) * half_inverse;
  }
}

}  // namespace meshik
