// The pool of freed arrays' pages (page_pool.h): the page ranges given back, moved with mremap.
#include "page_pool.h"

#include <algorithm>
#include <mutex>
#include <new>
#include <unordered_map>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace meshik {

#if defined(__linux__)

namespace {

struct PageRange {
  char* start;
  size_t bytes;
};

struct Pool {
  std::mutex mutex;
  std::vector<PageRange> ranges;  // the kept pages, the longest kept first
  size_t bytes = 0;
  // The arrays taken from more than one range, by start: their ranges (mremap moves pages within
  // one mapping only, so they are given back range by range).
  std::unordered_map<char*, std::vector<PageRange>> pieces;
};

// Never destroyed: arrays of static objects may be given back after the end of main.
Pool& pool() {
  static Pool* const instance = new Pool;
  return *instance;
}

size_t whole_pages(size_t bytes) {
  static const size_t page = static_cast<size_t>(sysconf(_SC_PAGESIZE));
  return (bytes + page - 1) / page * page;
}

}  // namespace

void* take_pages(size_t bytes) {
  const size_t size = whole_pages(bytes);
  void* const fresh = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (fresh == MAP_FAILED) throw std::bad_alloc();
  char* const target = static_cast<char*>(fresh);
  Pool& p = pool();
  const std::lock_guard<std::mutex> lock(p.mutex);
  // The kept ranges replace the fresh mapping's first pages, the latest given back first; of a
  // range longer than what is left, its head is moved and its tail kept. Should a move fail (too
  // many mappings), the rest stays fresh.
  std::vector<PageRange> pieces;
  size_t filled = 0;
  while (filled < size && !p.ranges.empty()) {
    PageRange& range = p.ranges.back();
    const size_t piece = std::min(range.bytes, size - filled);
    if (mremap(range.start, piece, piece, MREMAP_MAYMOVE | MREMAP_FIXED, target + filled) == MAP_FAILED) break;
    pieces.push_back({target + filled, piece});
    range.start += piece;
    range.bytes -= piece;
    p.bytes -= piece;
    filled += piece;
    if (range.bytes == 0) p.ranges.pop_back();
  }
  if (filled < size) pieces.push_back({target + filled, size - filled});
  if (pieces.size() > 1) {
    try {
      p.pieces.emplace(target, std::move(pieces));
    } catch (...) {
      munmap(target, size);
      throw;
    }
  }
  return target;
}

void give_pages(void* start, size_t bytes) noexcept {
  char* const first = static_cast<char*>(start);
  Pool& p = pool();
  const std::lock_guard<std::mutex> lock(p.mutex);
  std::vector<PageRange> ranges;
  const auto pieces = p.pieces.find(first);
  if (pieces != p.pieces.end()) {
    ranges = std::move(pieces->second);
    p.pieces.erase(pieces);
  }
  try {
    if (ranges.empty()) ranges.push_back({first, whole_pages(bytes)});
    // The array's first range is taken first next time.
    p.ranges.insert(p.ranges.end(), ranges.rbegin(), ranges.rend());
  } catch (...) {
    for (const PageRange& range : ranges) munmap(range.start, range.bytes);
    if (ranges.empty()) munmap(first, whole_pages(bytes));
    return;
  }
  for (const PageRange& range : ranges) p.bytes += range.bytes;
  // Beyond the capacity, the longest kept pages go back to the system (a range's tail first).
  size_t first_kept = 0;
  while (p.bytes > kPoolCapacityBytes) {
    PageRange& range = p.ranges[first_kept];
    const size_t excess = std::min(range.bytes, p.bytes - kPoolCapacityBytes);
    munmap(range.start + range.bytes - excess, excess);
    range.bytes -= excess;
    p.bytes -= excess;
    if (range.bytes == 0) ++first_kept;
  }
  p.ranges.erase(p.ranges.begin(), p.ranges.begin() + static_cast<std::ptrdiff_t>(first_kept));
}

void release_pooled_pages() noexcept {
  Pool& p = pool();
  const std::lock_guard<std::mutex> lock(p.mutex);
  for (const PageRange& range : p.ranges) munmap(range.start, range.bytes);
  p.ranges.clear();
  p.bytes = 0;
}

size_t pooled_bytes() noexcept {
  Pool& p = pool();
  const std::lock_guard<std::mutex> lock(p.mutex);
  return p.bytes;
}

#else

void* take_pages(size_t bytes) { return ::operator new(bytes); }
void give_pages(void* start, size_t /*bytes*/) noexcept { ::operator delete(start); }
void release_pooled_pages() noexcept {}
size_t pooled_bytes() noexcept { return 0; }

#endif

}  // namespace meshik
