// A short vector of doubles for the dense kernels and solves (GCC / Clang vector extension):
// as wide as the target's vector registers (8 with AVX-512, 4 with AVX, 2 otherwise).
#pragma once

#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace meshik::sparse {

// kLanes doubles per vector register; kVectorRegisters of them (x86-64: 32 with AVX-512, else 16).
#if defined(__AVX512F__)
constexpr int kLanes = 8;
constexpr int kVectorRegisters = 32;
#elif defined(__AVX__)
constexpr int kLanes = 4;
constexpr int kVectorRegisters = 16;
#else
constexpr int kLanes = 2;
constexpr int kVectorRegisters = 16;
#endif

typedef double Vec __attribute__((vector_size(kLanes * sizeof(double))));

// Half a Vec, for passes over at most kHalfLanes columns (used where kLanes >= 4).
constexpr int kHalfLanes = kLanes / 2;
typedef double HalfVec __attribute__((vector_size(kHalfLanes * sizeof(double))));

// v - s x for a Vec or a HalfVec, fused where the target has FMA: explicitly, since the compiler
// may contract the written expression in some inlined copies of a pass and not in others
// (different bits).
template <class T>
inline T subtract_product(T v, T s, T x) {
#if defined(__FMA__) && defined(__AVX512F__)
  if constexpr (sizeof(T) == 64) return _mm512_fnmadd_pd(s, x, v);
  else return _mm256_fnmadd_pd(s, x, v);
#elif defined(__FMA__) && defined(__AVX__)
  if constexpr (sizeof(T) == 32) return _mm256_fnmadd_pd(s, x, v);
  else return _mm_fnmadd_pd(s, x, v);
#else
  return v - s * x;
#endif
}

// Asks for the cache line two lines (16 doubles) past p. The dense kernels and the forward solves
// walk column-major blocks a few rows at a time across many columns: each step reads a new line
// from every column, too many streams for the hardware prefetcher. On the 1.08M system, asking
// for each column's next lines by hand took a 27-column forward solve from 332-355 to 161-227 ms
// and the numeric factorization from 1.07-1.29 to 0.90-0.99 s, on one thread (bench/README.md).
inline void prefetch_rows_ahead(const double* p) { __builtin_prefetch(p + 16); }

// A T (a Vec by default, or a HalfVec) from p (no alignment needed).
template <class T = Vec>
inline T load(const double* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Writes v (a Vec or a HalfVec) to p (no alignment needed).
template <class T>
inline void store(double* p, T v) { std::memcpy(p, &v, sizeof v); }

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

// Lanes [0, count) read from p (0 <= count <= kLanes), the others zero; nothing is read
// beyond p[count - 1].
inline Vec load_first(const double* p, int count) {
#if defined(__AVX512F__)
  return _mm512_maskz_loadu_pd(static_cast<__mmask8>((1u << count) - 1), p);
#elif defined(__AVX2__)
  const __m256i lanes = _mm256_setr_epi64x(0, 1, 2, 3);
  return _mm256_maskload_pd(p, _mm256_cmpgt_epi64(_mm256_set1_epi64x(count), lanes));
#else
  Vec v = {};
  for (int i = 0; i < count; ++i) v[i] = p[i];
  return v;
#endif
}

// Writes lanes [begin, end) of v to p[begin .. end) (0 <= begin <= end <= kLanes); nothing
// else is touched.
inline void store_lanes(double* p, Vec v, int begin, int end) {
#if defined(__AVX512F__)
  _mm512_mask_storeu_pd(p, static_cast<__mmask8>(((1u << end) - 1) & ~((1u << begin) - 1)), v);
#elif defined(__AVX2__)
  const __m256i lanes = _mm256_setr_epi64x(0, 1, 2, 3);
  const __m256i mask = _mm256_and_si256(_mm256_cmpgt_epi64(_mm256_set1_epi64x(end), lanes),
                                        _mm256_cmpgt_epi64(lanes, _mm256_set1_epi64x(begin - 1)));
  _mm256_maskstore_pd(p, mask, v);
#else
  for (int i = begin; i < end; ++i) p[i] = v[i];
#endif
}

// Rounds count up to a multiple of kLanes.
inline int round_up_to_lanes(int count) { return (count + kLanes - 1) / kLanes * kLanes; }

}  // namespace meshik::sparse
