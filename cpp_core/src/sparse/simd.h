// A short vector of doubles for the dense kernels and solves (GCC / Clang vector extension):
// as wide as the target's vector registers (8 with AVX-512, 4 with AVX, 2 otherwise).
#pragma once

#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace meshik::sparse {

#if defined(__AVX512F__)
constexpr int kLanes = 8;
#elif defined(__AVX__)
constexpr int kLanes = 4;
#else
constexpr int kLanes = 2;
#endif

typedef double Vec __attribute__((vector_size(kLanes * sizeof(double))));

// kLanes doubles from p (no alignment needed).
inline Vec load(const double* p) {
  Vec v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Writes kLanes doubles to p (no alignment needed).
inline void store(double* p, Vec v) { std::memcpy(p, &v, sizeof v); }

// All lanes equal to s.
inline Vec broadcast(double s) {
#if defined(__AVX512F__)
  return _mm512_set1_pd(s);
#elif defined(__AVX__)
  return _mm256_set1_pd(s);
#elif defined(__SSE2__)
  return _mm_set1_pd(s);
#else
  Vec v;
  for (int i = 0; i < kLanes; ++i) v[i] = s;
  return v;
#endif
}

// Rounds count up to a multiple of kLanes.
inline int round_up_to_lanes(int count) { return (count + kLanes - 1) / kLanes * kLanes; }

}  // namespace meshik::sparse
