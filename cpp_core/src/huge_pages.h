// Arrays of megabytes written once, on transparent huge pages. The first touch of each fresh
// 4 KiB page of a large allocation costs a kernel fault (zeroing included); the precompute writes
// tens of megabytes once (the examples' features, the rest frames), and those faults were about
// a sixth of its time on the elephant. With 2 MiB pages there are 512 times fewer. The factor's
// values (301 MB at 1.08M triangles) and a pose's work buffers (121 MB there) too: on this
// machine 301 MB took about 0.5 s on 4 KiB pages and 0.1 s on 2 MiB pages (under load).
// The first touch is the kernel's zeroing of each page, on the thread that touches it: arrays
// written by a parallel pass after they are sized (PageArray) are first touched by the whole team.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
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

// std::allocator whose construct() without a value default-initializes: resize() leaves new
// entries of a trivial type unwritten (their pages untouched) for a parallel pass to write first.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// An array of large storage whose pages are first touched by a team (assign_on_huge_pages below).
template <typename T>
using PageArray = std::vector<T, DefaultInitAllocator<T>>;

// v sized n in new storage advised onto huge pages, its entries unwritten (a trivial T: their pages
// untouched), for the caller to write first.
template <typename T>
void size_unwritten_on_huge_pages(PageArray<T>& v, size_t n) {
  PageArray<T> fresh;
  fresh.reserve(n);
  advise_huge_pages(fresh.data(), n * sizeof(T));
  fresh.resize(n);
  v.swap(fresh);
}

// v = n copies of value in new storage advised onto huge pages, written (so first touched, the
// kernel's zeroing included) by `team` threads in equal contiguous parts; below 64 Ki entries by
// the caller alone. The same contents for any team.
template <typename T>
void assign_on_huge_pages(PageArray<T>& v, size_t n, const T& value, int team) {
  PageArray<T> fresh;
  size_unwritten_on_huge_pages(fresh, n);
  T* data = fresh.data();
  const long count = static_cast<long>(n);
#pragma omp parallel for schedule(static) num_threads(team) if (count >= (long{1} << 16) && team > 1)
  for (long i = 0; i < count; ++i) data[i] = value;
  v.swap(fresh);
}

// v sized n, for work storage whose entries are always written before they are read: when it must
// grow, new storage on huge pages written first by `team` threads (its old entries are dropped,
// the new ones are T()), else resized in place.
template <typename T>
void size_work_on_huge_pages(PageArray<T>& v, size_t n, int team) {
  if (n > v.capacity())
    assign_on_huge_pages(v, n, T(), team);
  else
    v.resize(n, T());
}

}  // namespace meshik
