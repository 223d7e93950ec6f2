// Safe levels of the nested basins: a flood from the unsafe edges, level by level.
#include "safe_basins.h"

#include <algorithm>
#include <cstddef>
#include <numeric>

namespace meshik {

SafeBasins safe_basins(const TriangleAdjacency& adjacency, const double* distances,
                       const std::vector<double>& thresholds, const std::vector<int>& unsafe) {
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  SafeBasins basins;
  basins.levels = static_cast<int>(thresholds.size());
  const std::size_t entries = adjacency.neighbour.size();
  basins.edge_level.assign(entries, 0);
  for (double threshold : thresholds)
    for (std::size_t s = 0; s < entries; ++s) basins.edge_level[s] += !(distances[s] < threshold);
  // A triangle's basin at level l holds an unsafe edge of level <= l when the triangle is linked
  // to one by edges of level <= l. Flooding from the unsafe edges, level by level (an edge of a
  // coarser level waits in that level's queue), reaches each triangle first at the finest such
  // level: the triangle is safe up to the level before. Edges longer than every threshold link
  // no basin.
  std::vector<std::vector<int>> queue(basins.levels + 1);
  for (std::size_t p = 0; p + 1 < unsafe.size(); p += 2) {
    const int a = unsafe[p], b = unsafe[p + 1];
    int level = basins.levels;
    for (int s = adjacency.start[a]; s < adjacency.start[a + 1]; ++s)
      if (adjacency.neighbour[s] == b && basins.edge_level[s] < level) level = basins.edge_level[s];
    queue[level].insert(queue[level].end(), {a, b});
  }
  basins.safe_level.assign(m, static_cast<signed char>(basins.levels - 1));
  std::vector<char> reached(m, 0);
  for (int level = 0; level < basins.levels; ++level) {
    std::vector<int>& current = queue[level];
    for (std::size_t head = 0; head < current.size(); ++head) {
      const int j = current[head];
      if (reached[j]) continue;
      reached[j] = 1;
      basins.safe_level[j] = static_cast<signed char>(level - 1);
      for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s) {
        const int n = adjacency.neighbour[s];
        if (reached[n]) continue;
        const int link = basins.edge_level[s];
        if (link <= level)
          current.push_back(n);
        else if (link < basins.levels)
          queue[link].push_back(n);
      }
    }
    current = std::vector<int>();
  }
  return basins;
}

SafeBasinMembers safe_basin_members(const TriangleAdjacency& adjacency, const SafeBasins& basins) {
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  const int* start = adjacency.start.data();
  const int* neighbour = adjacency.neighbour.data();
  const signed char* safe_level = basins.safe_level.data();
  const signed char* edge_level = basins.edge_level.data();
  // A basin of level l: the triangles of safe level l linked by edges of level <= l (every
  // triangle of a basin has the basin's safe level). Union-find over those links, each taken from
  // its larger end, the lesser root kept: every set's root is its least triangle.
  std::vector<int> parent(m);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root_of = [&parent](int a) {
    while (parent[a] != a) {
      parent[a] = parent[parent[a]];
      a = parent[a];
    }
    return a;
  };
  for (int j = 0; j < m; ++j) {
    const int level = safe_level[j];
    if (level < 0) continue;
    for (int s = start[j]; s < start[j + 1]; ++s) {
      const int n = neighbour[s];
      if (n >= j || edge_level[s] > level || safe_level[n] != level) continue;
      const int a = root_of(j), b = root_of(n);
      if (a < b) parent[b] = a;
      else parent[a] = b;
    }
  }
  // Basins numbered as their roots come (a root precedes its set's other triangles), then listed.
  SafeBasinMembers members;
  members.basin_of.assign(m, -1);
  int count = 0;
  for (int j = 0; j < m; ++j)
    if (safe_level[j] >= 0) {
      const int root = root_of(j);
      members.basin_of[j] = root == j ? count++ : members.basin_of[root];
    }
  members.start.assign(count + 1, 0);
  for (int j = 0; j < m; ++j)
    if (members.basin_of[j] >= 0) ++members.start[members.basin_of[j] + 1];
  std::partial_sum(members.start.begin(), members.start.end(), members.start.begin());
  members.member.resize(members.start[count]);
  std::vector<int>& fill = parent;  // the next free place of each basin's list
  std::copy(members.start.begin(), members.start.end() - 1, fill.begin());
  for (int j = 0; j < m; ++j)
    if (members.basin_of[j] >= 0) members.member[fill[members.basin_of[j]]++] = j;
  return members;
}

}  // namespace meshik
