// Giving freed heap memory back to the system after a phase that allocates and frees large
// temporaries. glibc keeps freed chunks of its heaps resident while anything above them is still
// in use (each thread has its own heap: the ExampleSet's analysis thread leaves one behind too);
// at 1.08M triangles about 56 MB stayed resident that way after the Solver was built, and were
// still held when the pose's buffers were allocated on top of them (the process's peak).
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace meshik {

// Returns the free pages of every malloc heap to the system (glibc's malloc_trim(0): whole free
// pages inside a heap are released too, not only its top). Takes nothing, returns nothing; a few
// milliseconds at 1M triangles. Elsewhere it does nothing.
inline void release_free_heap_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace meshik
