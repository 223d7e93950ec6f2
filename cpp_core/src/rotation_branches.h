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
#include <Eigen/StdVector>

#include "mesh_topology.h"

namespace meshik {

// The logarithm of the rotation exp(principal) closest to reference: (theta + 2 pi k) axis with the
// best integer k (principal itself when k = 0). principal: a log with |principal| <= pi;
// reference: any rotation vector.
Eigen::Vector3d closest_log_branch(const Eigen::Vector3d& principal,
                                   const Eigen::Vector3d& reference);

// The length of the adjacency edge from triangle a to b: 3 - trace(R_a^T R_b), monotone in the
// angle between the two rotations.
double rotation_distance(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to);

// rotations: #F rotation matrices, one per triangle. Writes distances[s] =
// rotation_distance(R_j, R_neighbour[s]) for the adjacency entries s of triangles j in
// [first, last) (distances: one per adjacency entry).
void rotation_edge_distances(const TriangleAdjacency& adjacency, const Eigen::Matrix3d* rotations, int first,
                             int last, double* distances);

// distances: one per adjacency entry (rotation_edge_distances); logs: the #F principal logs of
// the triangles' rotations (#F: the adjacency's triangles), replaced by consistent branches.
// Grows a minimum spanning tree of the edge adjacency (Prim's, ties broken by the lower tree
// triangle, then the lower new one) from the least rotated triangle of each component, which keeps
// its principal log, and gives every triangle added the branch closest to the log of the tree
// neighbour it was reached from, so branches are only copied between nearly equal rotations.
// Where the tree cannot change a branch (a basin of close rotations whose angles are small enough,
// entered from a principal log) the basin's triangles keep their principal logs without the tree
// being grown through them: the branches are those of the whole tree, bit for bit.
// components: triangle_components(adjacency). Returns the triangles whose logs are no longer the
// principal ones.
std::vector<int> choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                                const TriangleComponents& components, const double* distances,
                                                Eigen::Vector3d* logs);

// The same from the rotations (#F) themselves.
void choose_consistent_log_branches(const TriangleAdjacency& adjacency,
                                    const std::vector<Eigen::Matrix3d>& rotations,
                                    std::vector<Eigen::Vector3d>& logs);

}  // namespace meshik
