// Deformation-aware decimation of an example set, two implementations with one contract:
// decimate_example_set on OpenMesh's decimater, decimate_example_set_fast on our own collapse
// heap (no OpenMesh; guards checked only when a collapse is popped: 15-25 times faster on the
// horse gallop, bench/README.md).
//
// One collapse sequence is chosen for the rest pose and every example at once: the error of a
// collapse is the sum over all poses of the quadric error (Garland-Heckbert) at the kept vertex,
// and a collapse that would flip or degenerate a triangle in any pose is refused. Collapses are
// half-edge collapses onto an existing vertex, so the simplified mesh keeps a subset of the
// original vertices: in every pose each kept vertex sits exactly at its original position.
// Locked vertices (the handles) are never removed. Optionally a collapse is also refused when it
// would move the simplified surface farther than a bound from the original in any pose.
#pragma once

#include <limits>
#include <vector>

#include "meshik/meshik.h"

namespace meshik {

struct DecimationResult {
  std::vector<int> kept_vertices;  // #S original vertex ids of the simplified mesh, increasing
  std::vector<int> triangles;      // #SF by 3 row-major indices into kept_vertices
  std::vector<int> vertex_map;     // #V: the simplified vertex (index into kept_vertices) that
                                   //     each original vertex was collapsed into
  double worst_distance = 0.0;     // the largest distance, over all poses, of a removed vertex
                                   // from the simplified triangle it is attached to, or of a
                                   // simplified triangle's sample point from the original surface
  double bound = 0.0;              // the distance bound in force at the end (infinity: none)
  int relaxations = 0;             // how many times the bound was relaxed to reach the target
};

// The distance bound of a decimation: a collapse is refused when, in any pose, a removed vertex
// would lie farther than max_distance from the simplified surface, or a sample point of a
// simplified triangle (centroid, edge midpoints, three inner points) from the original surface.
// When no allowed collapse is left above the target, decimation goes on under a relaxed bound: the
// larger of relax_factor times the bound and a lower bound of the least bound that would have
// allowed a refused collapse; at most max_relaxations times, after that the bound is lifted.
struct DistanceBound {
  double max_distance = std::numeric_limits<double>::infinity();  // infinity: no bound
  double relax_factor = 1.25;                                     // > 1
  int max_relaxations = 10;                                       // >= 0
};

// rest:             the rest mesh (#V vertices, #F triangles, manifold)
// examples:         #E pointers, each to a #V by 3 row-major array of one example pose
// locked:           vertex ids that must remain (each in [0, #V))
// target_triangles: stop when at most this many triangles remain (or no legal collapse is left)
// max_normal_change_degrees: refuse a collapse that turns a triangle's normal by more than
//                   this in any pose
// bound:            the distance bound (see DistanceBound; worst_distance is reported either way)
// Throws InputError for a non-manifold triangle list, indices out of range or a bad target.
DecimationResult decimate_example_set(const MeshView& rest, const std::vector<const double*>& examples,
                                      const std::vector<int>& locked, int target_triangles,
                                      double max_normal_change_degrees = 60.0,
                                      const DistanceBound& bound = DistanceBound());

// The same decimation (same arguments, guards, bound and result) without OpenMesh: the collapses
// come from a heap of half-edge collapses ordered by the summed quadric error (ties by vertex ids),
// and the guards (topology, triangle soundness, distance bound) are checked when a collapse is
// popped; a refused collapse waits until its neighbourhood changes or the bound is relaxed.
// Half-edge collapses only: the kept vertices are a subset of the original ones, locked ones kept.
// threads: 0 for all cores, 1 for none; the result is the same for any count.
// Where the mesh is not an oriented manifold (an edge of three or more triangles, two triangles of
// opposite orientation along an edge, a vertex whose triangles form more than one fan) the vertices
// are kept as if locked, and the rest is decimated. Throws InputError for a triangle with a vertex
// out of range or repeated, a locked id out of range or a bad target or bound.
DecimationResult decimate_example_set_fast(const MeshView& rest, const std::vector<const double*>& examples,
                                           const std::vector<int>& locked, int target_triangles,
                                           double max_normal_change_degrees = 60.0,
                                           const DistanceBound& bound = DistanceBound(), int threads = 0);

}  // namespace meshik
