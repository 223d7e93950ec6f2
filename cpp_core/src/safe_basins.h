// Nested basins of an edge-weighted triangle adjacency, and the coarsest level at which each
// triangle's basin holds no `unsafe` edge.
//
// Level l (0 .. thresholds.size() - 1) joins the triangles linked by edges shorter than
// thresholds[l]: its basins are the connected components of those edges, and
// a basin of one level lies inside one basin of every coarser level. Every edge between two
// basins of a level is at least its threshold long, and each basin is connected by shorter
// edges, so Prim's algorithm, once it enters a basin, adds the whole basin along the basin's own
// edges before it crosses any edge leaving it. The rotation branches (rotation_branches.cpp) use
// this to skip the spanning tree inside basins where it cannot change a branch.
#pragma once

#include <vector>

#include "mesh_topology.h"

namespace meshik {

struct SafeBasins {
  // Per adjacency entry: its level, the first whose threshold the edge is shorter than (the
  // number of levels for the others, NaN included). The basins of level l are linked by the
  // entries of level <= l.
  std::vector<signed char> edge_level;
  // Per triangle: the coarsest level at which its basin has no unsafe edge of the basin's
  // links (level <= l) inside, -1 if none. The same for every triangle of that basin.
  std::vector<signed char> safe_level;
  int levels = 0;
};

// adjacency: #F triangles; distances: one per adjacency entry, the same both ways; thresholds:
// increasing, at most 100; unsafe: the unsafe edges as pairs of adjacent triangles (a, b),
// flattened.
SafeBasins safe_basins(const TriangleAdjacency& adjacency, const double* distances,
                       const std::vector<double>& thresholds, const std::vector<int>& unsafe);

// The safe basins as lists of triangles: for each triangle j with a safe level (>= 0), its basin at
// that level, the basins of every level numbered together by their least triangle; the
// triangles of basin b, increasing, are member[start[b] .. start[b + 1]).
struct SafeBasinMembers {
  std::vector<int> basin_of;  // #F: the basin, or -1 for a triangle without a safe level
  std::vector<int> start;     // #basins + 1
  std::vector<int> member;    // the triangles with a safe level, basin by basin
};

// adjacency: as for safe_basins; basins: safe_basins' result for it. One pass over the links in
// index order (a union-find), not a search through each basin: the lists come out in the order
// of the triangles, whose neighbours lie close in memory.
SafeBasinMembers safe_basin_members(const TriangleAdjacency& adjacency, const SafeBasins& basins);

}  // namespace meshik
