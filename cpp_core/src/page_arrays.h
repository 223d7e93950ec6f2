// Arrays of megabytes whose pages a team touches first, and the long-lived ones on transparent
// huge pages. The first touch of each fresh page is a kernel fault that zeroes it, on the thread
// that touches it: arrays sized unwritten (PageArray) and then written by a parallel pass are
// first touched by the whole team.
// Huge pages (2 MiB) for the Solver's storage, made per handle set and read by every solve: the
// factor's values (301 MB at 1.08M triangles) and a pose's work buffers (121 MB there). The
// ExampleSet's arrays, written once before the first pose, stay on the default pages: on a virtual machine
// that hands freed memory back to its host (free page reporting), a fresh huge page cost about
// twice a fresh 4 KiB page, and with every array on huge pages the 1.08M first pose on 2 threads
// took 2,331-2,875 ms against 2,184-2,197 ms so (bench/README.md, "Huge pages only where they are
// read again").
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

// An array of large storage whose pages are first touched by a team (assign_by_team below).
template <typename T>
using PageArray = std::vector<T, DefaultInitAllocator<T>>;

// Which pages new storage asks for: the system's default, or huge pages (advise_huge_pages).
enum class Pages { kDefault, kHuge };

// v sized n in new storage on `pages`, its entries unwritten (a trivial T: their pages untouched),
// for the caller to write first.
template <typename T>
void size_unwritten(PageArray<T>& v, size_t n, Pages pages) {
  PageArray<T> fresh;
  fresh.reserve(n);
  if (pages == Pages::kHuge) advise_huge_pages(fresh.data(), n * sizeof(T));
  fresh.resize(n);
  v.swap(fresh);
}

// v = n copies of value in new storage on `pages`, written (so first touched, the kernel's zeroing
// included) by `team` threads in equal contiguous parts; below 64 Ki entries by the caller alone.
// The same contents for any team.
template <typename T>
void assign_by_team(PageArray<T>& v, size_t n, const T& value, int team, Pages pages) {
  PageArray<T> fresh;
  size_unwritten(fresh, n, pages);
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
    assign_by_team(v, n, T(), team, Pages::kHuge);
  else
    v.resize(n, T());
}

}  // namespace meshik
