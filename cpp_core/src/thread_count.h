// How many threads a parallel pass of the core uses.
#pragma once

namespace meshik {

// requested: 0 = all cores (OpenMP's default team size, which OMP_NUM_THREADS sets), n >= 1 = n
// threads. Returns the team size to ask for: 1 when the core is built without OpenMP, or when the
// caller is already inside an OpenMP parallel region (nested teams stay off, so a pass started from
// a parallel loop of the caller never oversubscribes the cores).
int thread_count(int requested);

// The calling thread's number in its OpenMP team: 0 .. team size - 1 (0 outside a parallel region
// or without OpenMP).
int thread_index();

// The chunk for a dynamically scheduled loop of `iterations` on `team` threads: about 8 chunks per
// thread, so that a thread slowed by another task on its core leaves little for the others to wait
// for, and from 16 to 512 iterations.
inline int dynamic_chunk(int iterations, int team) {
  const int chunk = iterations / (8 * (team > 0 ? team : 1));
  return chunk < 16 ? 16 : (chunk > 512 ? 512 : chunk);
}

}  // namespace meshik
