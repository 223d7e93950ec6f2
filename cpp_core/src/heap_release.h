// Giving freed heap memory back to the system after a phase that allocates and frees large
// temporaries. glibc keeps freed chunks of its heaps resident while anything above them is still
// in use (each thread has its own heap: the ExampleSet's analysis thread leaves one behind too).
// At 1.08M triangles on 2 threads about 105 MB are free in the heaps after the ExampleSet and again
// after the factorization; kept, they would stay resident under the factorization (the process's
// peak) and under the poses, so they are given back.
// Below a bound they are kept instead: the next allocations reuse those pages without the kernel's
// faults and zeroing. On the elephant (40 MB free after the ExampleSet, 13 MB after the
// factorization) giving them back made the Solver built next about 15-20 % slower. At 1.08M on one
// thread (23 and 51 MB free: no analysis thread's heap) they are kept too, and the peak is about
// 40 MB higher than when they were given back (934 against 896 MB); with more threads it is not.
#pragma once

#include <cstddef>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace meshik {

// The freed heap memory kept for reuse: above it, release_free_heap_memory gives it all back.
constexpr size_t kKeptFreeHeapBytes = size_t{64} << 20;

// When the malloc heaps hold more than kKeptFreeHeapBytes of free memory, returns their free pages
// to the system (glibc's malloc_trim(0): whole free pages inside a heap are released too, not only
// its top); with less, keeps them. The free memory counted includes chunks whose pages an earlier
// trim already released, so a process holding many such holes trims every time, as before the bound.
// Takes nothing, returns nothing; a few milliseconds at 1M triangles. Before glibc 2.33 (no
// mallinfo2) it always trims; elsewhere than glibc it does nothing.
inline void release_free_heap_memory() {
#if defined(__GLIBC__)
#if __GLIBC_PREREQ(2, 33)
  if (mallinfo2().fordblks <= kKeptFreeHeapBytes) return;
#endif
  malloc_trim(0);
#endif
}

}  // namespace meshik
