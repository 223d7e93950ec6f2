// The evaluation passes' fixed chunks of triangles and the extra rows of their shared unknowns.
#include "assembly_partition.h"

#include <algorithm>

namespace meshik {

namespace {

constexpr int kMaxChunks = 32;
constexpr int kMinChunkBatches = 32;

}  // namespace

AssemblyPartition assembly_partition(const std::vector<int>& triangles, const std::vector<int>& unknown_of_vertex,
                                     int num_rows) {
  const int num_triangles = static_cast<int>(triangles.size() / 3);
  const int batches = (num_triangles + kLanes - 1) / kLanes;
  const int pairs = (batches + kCurvatureBatches - 1) / kCurvatureBatches;
  const int chunks = std::max(1, std::min(kMaxChunks, batches / kMinChunkBatches));
  AssemblyPartition p;
  p.batch_start.resize(chunks + 1);
  p.row_start.resize(chunks + 1);
  for (int c = 0; c <= chunks; ++c) {
    const long long pair = static_cast<long long>(pairs) * c / chunks;
    p.batch_start[c] = static_cast<int>(std::min<long long>(batches, pair * kCurvatureBatches));
    p.row_start[c] = static_cast<int>(static_cast<long long>(num_rows) * c / chunks);
  }
  p.corner_row.assign(static_cast<size_t>(batches) * kLanes * 3, -1);
  // Per unknown: the last chunk that touched it and the row that chunk writes it to.
  std::vector<int> last_chunk(num_rows, -1), row_in_chunk(num_rows, -1);
  for (int c = 0; c < chunks; ++c) {
    const int first = p.batch_start[c] * kLanes * 3;
    const int end = std::min(p.batch_start[c + 1] * kLanes, num_triangles) * 3;
    for (int e = first; e < end; ++e) {
      const int u = unknown_of_vertex[triangles[e]];
      if (u < 0) continue;
      if (last_chunk[u] != c) {
        row_in_chunk[u] = last_chunk[u] < 0 ? u : num_rows + p.num_extra_rows();
        if (last_chunk[u] >= 0) p.extra_target.push_back(u);
        last_chunk[u] = c;
      }
      p.corner_row[e] = row_in_chunk[u];
    }
  }
  return p;
}

}  // namespace meshik
