// Checks of a decimation request shared by both decimators: each throws InputError with a
// one-line message naming the triangle, vertex or argument at fault.
#pragma once

#include <vector>

#include "meshik/decimate.h"

namespace meshik {
namespace decimation {

// Takes the rest mesh; throws unless every triangle has three distinct in-range vertices.
void check_corners(const MeshView& rest);

// Takes the rest mesh; throws unless every triangle has three distinct in-range vertices and no
// directed edge is used twice (which would mean inconsistent orientation or an edge shared by more
// than two triangles).
void check_triangles(const MeshView& rest);

// Takes the rest mesh (after check_corners); returns #V flags, 1 where the mesh is not an oriented
// manifold: both ends of a directed edge that more than one triangle runs along (an edge of three
// or more triangles, or two triangles of opposite orientation), and a vertex whose triangles form
// more than one fan.
std::vector<char> irregular_vertices(const MeshView& rest);

// Takes the vertex count, the locked vertex ids, the target triangle count and the distance bound;
// throws for a locked id out of range, a target below 1 or a bound that is not positive, or whose
// relax factor is not above 1 or relaxation count negative.
void check_request(int num_vertices, const std::vector<int>& locked, int target_triangles, const DistanceBound& bound);

}  // namespace decimation
}  // namespace meshik
