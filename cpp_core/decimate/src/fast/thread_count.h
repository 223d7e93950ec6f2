// The number of threads a decimation runs on.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace meshik {
namespace decimation {

// Takes the threads asked for (0: all cores); returns a count >= 1 (1 without OpenMP).
inline int resolve_threads(int threads) {
#ifdef _OPENMP
  return threads > 0 ? threads : omp_get_max_threads();
#else
  (void)threads;
  return 1;
#endif
}

}  // namespace decimation
}  // namespace meshik
