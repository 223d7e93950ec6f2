// Midpoint subdivision of a triangle mesh and of poses sharing its triangles: every triangle
// becomes four through its edges' midpoints, so a pose set keeps one connectivity (the
// benchmarks' large example sets).
#pragma once

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "obj_reader.h"

namespace meshik_bench {

// The topology of one subdivision step of `triangles` (#F by 3, #V vertices): each edge's new
// vertex (numbered from #V) and the 4 #F new triangles.
struct MidpointStep {
  std::vector<int> edge_ends;      // #new vertices by 2: the edge each new vertex halves
  std::vector<int> new_triangles;  // 4 #F by 3
};

inline MidpointStep midpoint_step(const std::vector<int>& triangles, int num_vertices) {
  MidpointStep step;
  std::unordered_map<long long, int> vertex_of_edge;
  vertex_of_edge.reserve(triangles.size());
  auto midpoint = [&](int a, int b) {
    const long long key = static_cast<long long>(std::min(a, b)) * num_vertices + std::max(a, b);
    const auto [at, added] =
        vertex_of_edge.emplace(key, num_vertices + static_cast<int>(step.edge_ends.size() / 2));
    if (added) step.edge_ends.insert(step.edge_ends.end(), {a, b});
    return at->second;
  };
  step.new_triangles.reserve(4 * triangles.size());
  for (size_t j = 0; j < triangles.size(); j += 3) {
    const int a = triangles[j], b = triangles[j + 1], c = triangles[j + 2];
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    step.new_triangles.insert(step.new_triangles.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return step;
}

// positions (#V by 3) with the step's midpoints appended.
inline std::vector<double> subdivided_positions(const std::vector<double>& positions, const MidpointStep& step) {
  std::vector<double> out = positions;
  out.reserve(positions.size() + 3 * step.edge_ends.size() / 2);
  for (size_t e = 0; e < step.edge_ends.size(); e += 2)
    for (int d = 0; d < 3; ++d)
      out.push_back(0.5 * (positions[3 * static_cast<size_t>(step.edge_ends[e]) + d] +
                           positions[3 * static_cast<size_t>(step.edge_ends[e + 1]) + d]));
  return out;
}

}  // namespace meshik_bench
