// Safe levels of the nested basins: a flood from the unsafe edges, level by level.
#include "safe_basins.h"

#include <cstddef>

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

}  // namespace meshik
