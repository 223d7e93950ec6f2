// A fixed partition of the triangles into chunks for the evaluation passes of one handle set,
// so that the passes run one chunk per task on any number of threads and give the same bits.
//
// The partition depends only on the mesh and the handle set, never on the thread count: every
// per-chunk partial result (sums over triangles, scatters into shared rows) is combined in chunk
// order afterwards. The scatter of G'^T [s | J] writes each free corner's contribution to a row
// of the right-hand sides: the row of its unknown when its chunk is the first chunk to touch that
// unknown (the row's owner), otherwise a private extra row of its chunk, stored after the
// system's rows and added to the unknown's row in chunk order once every chunk is done.
#pragma once

#include <vector>

#include "feature_space.h"

namespace meshik {

struct AssemblyPartition {
  // #chunks + 1: chunk c holds the batches (of kLanes triangles) [batch_start[c], batch_start[c+1]),
  // whole pairs of batches (kCurvatureBatches) except for the last chunk's end.
  std::vector<int> batch_start;
  // #batches by kLanes by 3: the row a triangle corner scatters into (an unknown's row, or
  // num_rows + e for extra row e), or -1 (a handle or a padding lane).
  std::vector<int> corner_row;
  // #extra rows: the unknown's row each extra row is added to, extras numbered in chunk order.
  std::vector<int> extra_target;
  // #chunks + 1: chunk c's share of the system rows for the passes over rows (outer products).
  std::vector<int> row_start;

  int num_chunks() const { return static_cast<int>(batch_start.size()) - 1; }
  int num_extra_rows() const { return static_cast<int>(extra_target.size()); }
};

// triangles: #F by 3 vertex indices; unknown_of_vertex (#V) and num_rows: the handle set's system
// (PoseSystem's). Chunks of about the same number of batches, at most 32 and each of at least 32
// batches when the mesh has that many.
AssemblyPartition assembly_partition(const std::vector<int>& triangles, const std::vector<int>& unknown_of_vertex,
                                     int num_rows);

}  // namespace meshik
