// Breadth-first vertex order and the matching triangle order.
#include "locality_order.h"

#include <algorithm>
#include <numeric>

#include "sparse/breadth_first_order.h"
#include "sparse/ordering.h"

namespace meshik {

LocalityOrder locality_order(const int* triangles, int num_triangles, int num_vertices) {
  // Vertex neighbours through triangle edges, in compressed rows (duplicates are harmless).
  std::vector<int> start(num_vertices + 1, 0);
  for (int e = 0; e < 3 * num_triangles; ++e) start[triangles[e] + 1] += 2;
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> neighbour(start[num_vertices]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int j = 0; j < num_triangles; ++j)
    for (int q = 0; q < 3; ++q) {
      const int v = triangles[3 * j + q];
      neighbour[fill[v]++] = triangles[3 * j + (q + 1) % 3];
      neighbour[fill[v]++] = triangles[3 * j + (q + 2) % 3];
    }

  LocalityOrder order;
  std::vector<int> run_starts;
  order.vertex_of_internal = sparse::breadth_first_order(start, neighbour, &run_starts);
  order.internal_of_vertex = sparse::invert_permutation(order.vertex_of_internal);
  // The runs of the breadth-first order are the components; the vertices of no triangle (empty
  // lists) follow them.
  VertexComponents& components = order.components;
  components.count = static_cast<int>(run_starts.size()) - 1;
  components.component_of_vertex.assign(num_vertices, -1);
  for (int c = 0; c < components.count; ++c)
    std::fill(components.component_of_vertex.begin() + run_starts[c],
              components.component_of_vertex.begin() + run_starts[c + 1], c);

  std::vector<int> smallest(num_triangles);
  for (int j = 0; j < num_triangles; ++j)
    smallest[j] = std::min({order.internal_of_vertex[triangles[3 * j]],
                            order.internal_of_vertex[triangles[3 * j + 1]],
                            order.internal_of_vertex[triangles[3 * j + 2]]});
  order.triangle_order = sparse::stable_order_by_key(smallest, num_vertices);
  return order;
}

}  // namespace meshik
