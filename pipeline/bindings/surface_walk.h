// A vertex order for meshoptimizer's vertex codec, which codes each vertex's bytes as the difference
// from the vertex before it: the smoother the attributes along the order, the fewer bits. Used by
// meshik._meshopt (meshopt_module.cpp) for the quantized .glb; plain C++, no Python.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshik_bindings {

// #V old vertex index at each new position: a depth-first walk over the mesh's edges that always
// steps to the nearest unvisited neighbour (ties: the lower index) and backs up to the latest vertex
// with one left when it has none. Each component starts at its vertex first used by `indices`
// (3 #F triangle corners, all < vertex_count); vertices no triangle uses come last in index order.
// positions: vertex_count by 3 (row-major). Same order for the same input on every machine.
std::vector<std::uint32_t> surface_walk_order(const std::uint32_t* indices, std::size_t index_count,
                                              const double* positions, std::size_t vertex_count);

}  // namespace meshik_bindings
