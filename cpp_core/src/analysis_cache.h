// A process-wide cache of the system analyses (ordering, symbolic factorization, subtree schedule)
// of ExampleSets by mesh connectivity: a second ExampleSet of the same triangles in the same
// process (another shot of a character, a batch worker's next job) shares the first one's analysis
// instead of building the pattern and analysing it again. The analysis depends on the triangles
// and the vertex count only, never on positions, examples or handles.
//
// Bounded: at most kAnalysisCacheEntries entries and kAnalysisCacheBytes bytes (the analyses'
// arrays and the kept triangles), the least recently used dropped first. An analysis stays alive
// while an ExampleSet uses it, whether or not the cache still holds it (it is shared, not copied).
// Thread-safe: ExampleSets may be built on several threads at once.
#pragma once

#include <cstddef>
#include <vector>

#include "meshik/sparse_cholesky.h"

namespace meshik {

constexpr size_t kAnalysisCacheEntries = 8;
constexpr size_t kAnalysisCacheBytes = size_t{512} << 20;

// triangles: #F by 3 vertex indices (the ExampleSet's internal order), num_vertices: #V.
// Returns true, with `into` sharing the cached analysis of exactly these triangles (compared entry
// by entry after the hash matched), or false with `into` untouched.
bool share_cached_analysis(const std::vector<int>& triangles, int num_vertices, SparseCholesky& into);

// Keeps the analysis of `analysed` (its analyze() done) as that of these triangles (as above).
// Does nothing for an object without an analysis or one larger than the whole budget.
void cache_analysis(const std::vector<int>& triangles, int num_vertices, const SparseCholesky& analysed);

// What the cache did since the process started (or the last clear_analysis_cache()).
struct AnalysisCacheStats {
  long long hits = 0, misses = 0;  // share_cached_analysis calls that found / did not find one
  size_t entries = 0, bytes = 0;   // held now
};
AnalysisCacheStats analysis_cache_stats();

// Drops every entry and zeroes the counters.
void clear_analysis_cache();

}  // namespace meshik
