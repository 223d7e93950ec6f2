// thread_count: the team size of the core's parallel passes.
#include "thread_count.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace meshik {

int thread_count(int requested) {
#ifdef _OPENMP
  if (omp_in_parallel()) return 1;
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace meshik
