#include "analysis_cache.h"

#include <cstdint>
#include <list>
#include <mutex>

namespace meshik {

namespace {

struct Entry {
  uint64_t hash;
  int num_vertices;
  std::vector<int> triangles;
  SparseCholesky analysis;  // shares the analysis (no factorization)
  size_t bytes;
};

struct Cache {
  std::mutex mutex;
  std::list<Entry> entries;  // most recently used first
  AnalysisCacheStats stats;
};

Cache& cache() {
  static Cache instance;
  return instance;
}

// triangles, num_vertices: as share_cached_analysis. Returns a 64-bit hash of both.
uint64_t connectivity_hash(const std::vector<int>& triangles, int num_vertices) {
  uint64_t h = 0x9e3779b97f4a7c15ull ^ static_cast<uint64_t>(num_vertices);
  for (int v : triangles) {
    h ^= static_cast<uint32_t>(v);
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

// Drops least recently used entries of c (its mutex held) until it fits the bounds.
void trim(Cache& c) {
  while (!c.entries.empty() &&
         (c.entries.size() > kAnalysisCacheEntries || c.stats.bytes > kAnalysisCacheBytes)) {
    c.stats.bytes -= c.entries.back().bytes;
    c.entries.pop_back();
  }
  c.stats.entries = c.entries.size();
}

}  // namespace

bool share_cached_analysis(const std::vector<int>& triangles, int num_vertices, SparseCholesky& into) {
  const uint64_t hash = connectivity_hash(triangles, num_vertices);
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  for (auto it = c.entries.begin(); it != c.entries.end(); ++it)
    if (it->hash == hash && it->num_vertices == num_vertices && it->triangles == triangles) {
      into.share_analysis(it->analysis);
      c.entries.splice(c.entries.begin(), c.entries, it);
      ++c.stats.hits;
      return true;
    }
  ++c.stats.misses;
  return false;
}

void cache_analysis(const std::vector<int>& triangles, int num_vertices, const SparseCholesky& analysed) {
  if (analysed.analyzed_pattern().rows == 0) return;
  const size_t bytes = triangles.size() * sizeof(int) + analysed.analysis_bytes();
  if (bytes > kAnalysisCacheBytes) return;
  Entry entry{connectivity_hash(triangles, num_vertices), num_vertices, triangles, SparseCholesky(), bytes};
  entry.analysis.share_analysis(analysed);
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  for (const Entry& e : c.entries)
    if (e.hash == entry.hash && e.num_vertices == num_vertices && e.triangles == triangles) return;
  c.entries.push_front(std::move(entry));
  c.stats.bytes += bytes;
  trim(c);
}

AnalysisCacheStats analysis_cache_stats() {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  return c.stats;
}

void clear_analysis_cache() {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.entries.clear();
  c.stats = AnalysisCacheStats();
}

}  // namespace meshik
