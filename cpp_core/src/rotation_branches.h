// Consistent branches of the rotation logarithm over a mesh.
//
// A rotation by theta about axis a has the logarithms (theta + 2 pi k) a for every integer k. The
// principal one (|phi| <= pi) jumps from +pi a to -pi a where a field of rotations passes through
// a half turn (a tail twisted by 180 degrees), and blending such logs flips neighbouring
// triangles in opposite directions. Choosing each triangle's branch closest to an already chosen
// neighbour keeps the field continuous (Sumner et al. 2005, footnote on the log's ambiguity).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh_topology.h"

namespace meshik {

// The logarithm of the rotation exp(principal) closest to reference: (theta + 2 pi k) axis with the
// best integer k. principal: a log with |principal| <= pi; reference: any rotation vector.
Eigen::Vector3d closest_log_branch(const Eigen::Vector3d& principal,
                                   const Eigen::Vector3d& reference);

// logs: #F principal rotation logs, one per triangle, replaced by consistent branches.
// Walks the edge adjacency breadth-first from the least rotated unvisited triangle of each
// component (which keeps its principal log) and gives every newly reached triangle the branch
// closest to the log of the triangle it was reached from.
void choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                    std::vector<Eigen::Vector3d>& logs);

}  // namespace meshik
