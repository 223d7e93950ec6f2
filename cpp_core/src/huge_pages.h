// Arrays of megabytes written once, on transparent huge pages. The first touch of each fresh
// 4 KiB page of a large allocation costs a kernel fault (zeroing included); the precompute writes
// tens of megabytes once (the examples' features, the rest frames), and those faults were about
// a sixth of its time on the elephant. With 2 MiB pages there are 512 times fewer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace meshik {

// Asks Linux to back the whole 2 MiB pages inside [data, data + bytes) with huge pages when they
// are first touched (madvise MADV_HUGEPAGE: advice, which the kernel may decline; nothing changes
// but the speed). Elsewhere it does nothing.
inline void advise_huge_pages(void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr uintptr_t kHugePage = uintptr_t{1} << 21;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(data);
  const uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t last = (begin + bytes) & ~(kHugePage - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

// v = n copies of value, in new storage advised onto huge pages before it is first written.
template <typename T>
void assign_on_huge_pages(std::vector<T>& v, size_t n, const T& value) {
  std::vector<T> fresh;
  fresh.reserve(n);
  advise_huge_pages(fresh.data(), n * sizeof(T));
  fresh.assign(n, value);
  v.swap(fresh);
}

}  // namespace meshik
