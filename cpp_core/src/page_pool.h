// Pages of freed large arrays, kept for the next large arrays.
//
// The first touch of a fresh page is a kernel fault that zeroes it: about 1.7 us a 4 KiB page on a
// virtual machine that reports its free pages to the host. At 1.08M triangles on 2 threads an
// ExampleSet touched 0.75 GB fresh and the Solver built next 0.47 GB. glibc maps arrays from
// 32 MiB (its largest mmap threshold) fresh and unmaps them when they are freed, so the
// ExampleSet's large temporaries (the rotations, the logs, the edge distances) went back
// to the system just before the Solver asked for as much again (the factor's values), and a
// Solver for new handles faulted in afresh what the old one had just freed. Through this pool a
// freed array's pages, still resident, are moved instead (Linux's mremap moves their page-table
// entries: nothing is copied, zeroed or faulted) into the next array asked for, which gets fresh
// pages only for what the pool lacks. Their old contents stay: an array's entries are written
// before they are read (page_arrays.h). An ExampleSet's destruction empties the pool. Elsewhere
// than Linux the pool is the C++ heap.
#pragma once

#include <cstddef>

namespace meshik {

// Arrays from this size are taken from the pool and given back to it; smaller ones are glibc's,
// which reuses its own freed memory for them.
constexpr size_t kPooledArrayBytes = size_t{32} << 20;

// The most the pool keeps: what is given back beyond it goes back to the system at once, the
// longest kept first. Room for what a Solver of 1M triangles frees (its factor's 273 MB and its
// poses' buffers), which the Solver built next for other handles takes (the drag tool frees the
// old Solver first); an ExampleSet of 1M triangles frees about 200 MB at its end.
constexpr size_t kPoolCapacityBytes = size_t{512} << 20;

// bytes (>= 1): returns page-aligned storage of at least `bytes`, its first pages the ones given
// back last (those of whole arrays, then part of one), fresh pages after them. Throws
// std::bad_alloc. Thread-safe.
void* take_pages(size_t bytes);

// start, bytes: what take_pages returned and the size asked for then. Keeps its pages for the next
// take_pages, within kPoolCapacityBytes. Thread-safe.
void give_pages(void* start, size_t bytes) noexcept;

// Returns every page the pool keeps to the system. Thread-safe.
void release_pooled_pages() noexcept;

// The bytes the pool keeps now. Thread-safe.
size_t pooled_bytes() noexcept;

}  // namespace meshik
