// The nearest-neighbour depth-first vertex walk of surface_walk.h.
#include "surface_walk.h"

#include <algorithm>
#include <utility>

namespace meshik_bindings {

namespace {

// Compressed adjacency: the distinct neighbours of vertex v are neighbours[first[v] .. first[v+1]).
struct VertexNeighbours {
  std::vector<std::size_t> first;
  std::vector<std::uint32_t> neighbours;
};

// The edges of 3 #F triangle corners as sorted, duplicate-free neighbour lists of vertex_count vertices.
VertexNeighbours vertex_neighbours(const std::uint32_t* indices, std::size_t index_count, std::size_t vertex_count) {
  VertexNeighbours graph;
  graph.first.assign(vertex_count + 1, 0);
  for (std::size_t c = 0; c < index_count; ++c) graph.first[indices[c] + 1] += 2;
  for (std::size_t v = 0; v < vertex_count; ++v) graph.first[v + 1] += graph.first[v];
  graph.neighbours.resize(graph.first[vertex_count]);
  std::vector<std::size_t> next(graph.first.begin(), graph.first.end() - 1);
  for (std::size_t t = 0; t + 2 < index_count; t += 3)
    for (int q = 0; q < 3; ++q) {
      const std::uint32_t v = indices[t + q];
      graph.neighbours[next[v]++] = indices[t + (q + 1) % 3];
      graph.neighbours[next[v]++] = indices[t + (q + 2) % 3];
    }
  // deduplicate each list in place, then close the gaps
  std::size_t out = 0;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const auto begin = graph.neighbours.begin() + static_cast<std::ptrdiff_t>(graph.first[v]);
    const auto end = graph.neighbours.begin() + static_cast<std::ptrdiff_t>(graph.first[v + 1]);
    std::sort(begin, end);
    const auto unique_end = std::unique(begin, end);
    graph.first[v] = out;
    for (auto it = begin; it != unique_end; ++it) graph.neighbours[out++] = *it;
  }
  graph.first[vertex_count] = out;
  graph.neighbours.resize(out);
  return graph;
}

double squared_distance(const double* positions, std::uint32_t a, std::uint32_t b) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = positions[3 * static_cast<std::size_t>(a) + k] - positions[3 * static_cast<std::size_t>(b) + k];
    sum += d * d;
  }
  return sum;
}

}  // namespace

std::vector<std::uint32_t> surface_walk_order(const std::uint32_t* indices, std::size_t index_count,
                                              const double* positions, std::size_t vertex_count) {
  const VertexNeighbours graph = vertex_neighbours(indices, index_count, vertex_count);
  std::vector<std::uint32_t> order;
  order.reserve(vertex_count);
  std::vector<bool> visited(vertex_count, false);
  std::vector<std::uint32_t> stack;
  std::vector<std::pair<double, std::uint32_t>> unvisited;  // (squared distance, vertex)
  auto walk_from = [&](std::uint32_t start) {
    stack.push_back(start);
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      if (visited[v]) continue;
      visited[v] = true;
      order.push_back(v);
      unvisited.clear();
      for (std::size_t e = graph.first[v]; e < graph.first[v + 1]; ++e)
        if (!visited[graph.neighbours[e]])
          unvisited.emplace_back(squared_distance(positions, v, graph.neighbours[e]), graph.neighbours[e]);
      // farthest pushed first, so the nearest is on top
      std::sort(unvisited.begin(), unvisited.end(), [](const auto& a, const auto& b) { return b < a; });
      for (const auto& entry : unvisited) stack.push_back(entry.second);
    }
  };
  for (std::size_t c = 0; c < index_count; ++c)
    if (!visited[indices[c]]) walk_from(indices[c]);
  for (std::uint32_t v = 0; v < vertex_count; ++v)
    if (!visited[v]) order.push_back(v);
  return order;
}

}  // namespace meshik_bindings
