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

}  // namespace meshik
