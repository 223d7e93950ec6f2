// Vertex components (union-find over triangle edges) and triangle edge adjacency.
#include "mesh_topology.h"

#include <cstddef>
#include <numeric>

namespace meshik {

namespace {

// Root of x in a union-find forest, halving paths on the way.
int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// The triangles around each vertex, in compressed rows (#V + 1 offsets, 3 #F entries).
void vertex_triangles(const int* triangles, int num_triangles, int num_vertices,
                      std::vector<int>& start, std::vector<int>& incident) {
  start.assign(num_vertices + 1, 0);
  for (int e = 0; e < 3 * num_triangles; ++e) ++start[triangles[e] + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  incident.resize(3 * static_cast<std::size_t>(num_triangles));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int j = 0; j < num_triangles; ++j)
    for (int q = 0; q < 3; ++q) incident[fill[triangles[3 * j + q]]++] = j;
}

}  // namespace

VertexComponents vertex_components(const int* triangles, int num_triangles, int num_vertices) {
  std::vector<int> parent(num_vertices);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(num_vertices, 0);
  for (int j = 0; j < num_triangles; ++j) {
    const int* t = triangles + 3 * j;
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
    for (int q = 1; q < 3; ++q) {
      const int a = find_root(parent, t[0]);
      const int b = find_root(parent, t[q]);
      if (a != b) parent[a] = b;
    }
  }
  VertexComponents components;
  components.component_of_vertex.assign(num_vertices, -1);
  std::vector<int> id_of_root(num_vertices, -1);
  for (int v = 0; v < num_vertices; ++v) {
    if (!used[v]) continue;
    const int root = find_root(parent, v);
    if (id_of_root[root] < 0) id_of_root[root] = components.count++;
    components.component_of_vertex[v] = id_of_root[root];
  }
  return components;
}

TriangleAdjacency triangle_adjacency(const int* triangles, int num_triangles, int num_vertices) {
  std::vector<int> start, incident;
  vertex_triangles(triangles, num_triangles, num_vertices, start, incident);
  TriangleAdjacency adjacency;
  adjacency.start.reserve(num_triangles + 1);
  adjacency.neighbour.reserve(3 * static_cast<std::size_t>(num_triangles));
  adjacency.start.push_back(0);
  for (int j = 0; j < num_triangles; ++j) {
    const int* t = triangles + 3 * j;
    for (int q = 0; q < 3; ++q) {
      const int a = t[q];
      const int b = t[(q + 1) % 3];
      // Triangles around a that also contain b share the edge (a, b).
      for (int s = start[a]; s < start[a + 1]; ++s) {
        const int other = incident[s];
        if (other == j) continue;
        const int* u = triangles + 3 * other;
        if (u[0] == b || u[1] == b || u[2] == b) adjacency.neighbour.push_back(other);
      }
    }
    adjacency.start.push_back(static_cast<int>(adjacency.neighbour.size()));
  }
  return adjacency;
}

TriangleComponents triangle_components(const TriangleAdjacency& adjacency) {
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  TriangleComponents components;
  components.component_of.assign(m, -1);
  std::vector<int> queue;
  queue.reserve(m);
  for (int start = 0; start < m; ++start) {
    if (components.component_of[start] >= 0) continue;
    const int id = components.count++;
    components.component_of[start] = id;
    queue.assign(1, start);
    for (std::size_t head = 0; head < queue.size(); ++head)
      for (int s = adjacency.start[queue[head]]; s < adjacency.start[queue[head] + 1]; ++s) {
        const int n = adjacency.neighbour[s];
        if (components.component_of[n] < 0) {
          components.component_of[n] = id;
          queue.push_back(n);
        }
      }
  }
  return components;
}

}  // namespace meshik
