// Arrays of megabytes whose pages a team touches first. The first touch of each fresh page is a
// kernel fault that zeroes it, on the thread that touches it: arrays sized unwritten (PageArray)
// and then written by a parallel pass are first touched by the whole team. Arrays from
// kPooledArrayBytes take the pages of such arrays freed before them where there are any
// (page_pool.h): their entries are written before they are read, never assumed zero.
// The pages are the system's default (no madvise for transparent huge pages): on a virtual machine
// that hands free memory back to its host (free page reporting), a fresh 2 MiB page cost about
// twice a fresh 4 KiB page, and with the ExampleSet's arrays, the factor's values and a pose's
// buffers on huge pages the 1.08M first pose took 2,303-2,754 ms on 2 threads against
// 1,873-2,067 ms on the default pages (bench/README.md, "Huge pages given up").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "page_pool.h"

namespace meshik {

// std::allocator whose construct() without a value default-initializes: resize() leaves new
// entries of a trivial type unwritten (their pages untouched) for a parallel pass to write first.
// Storage from kPooledArrayBytes is the page pool's.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (pooled(n)) return static_cast<T*>(take_pages(n * sizeof(T)));
    return std::allocator<T>::allocate(n);  // throws for a size past the addresses
  }
  void deallocate(T* p, size_t n) noexcept {
    if (pooled(n))
      give_pages(p, n * sizeof(T));
    else
      std::allocator<T>::deallocate(p, n);
  }
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

 private:
  // Whether n entries take kPooledArrayBytes or more (and their size is a size_t).
  static bool pooled(size_t n) {
    return n >= (kPooledArrayBytes + sizeof(T) - 1) / sizeof(T) && n <= SIZE_MAX / sizeof(T);
  }
};

// An array of large storage whose pages are first touched by a team (assign_by_team below).
template <typename T>
using PageArray = std::vector<T, DefaultInitAllocator<T>>;

// v sized n in new storage, its entries unwritten (a trivial T: their pages untouched), for the
// caller to write first.
template <typename T>
void size_unwritten(PageArray<T>& v, size_t n) {
  PageArray<T> fresh;
  fresh.resize(n);
  v.swap(fresh);
}

// v = n copies of value in new storage, written (so first touched, the kernel's zeroing included)
// by `team` threads in equal contiguous parts; below 64 Ki entries by the caller alone. The same
// contents for any team.
template <typename T>
void assign_by_team(PageArray<T>& v, size_t n, const T& value, int team) {
  PageArray<T> fresh;
  size_unwritten(fresh, n);
  T* data = fresh.data();
  const long count = static_cast<long>(n);
#pragma omp parallel for schedule(static) num_threads(team) if (count >= (long{1} << 16) && team > 1)
  for (long i = 0; i < count; ++i) data[i] = value;
  v.swap(fresh);
}

// v sized n, for work storage whose entries are always written before they are read: when it must
// grow, new storage written first by `team` threads (its old entries are dropped, the new ones are
// T()), else resized in place.
template <typename T>
void size_work_by_team(PageArray<T>& v, size_t n, int team) {
  if (n > v.capacity())
    assign_by_team(v, n, T(), team);
  else
    v.resize(n, T());
}

}  // namespace meshik
