// Deformation-aware decimation of an example set (OpenMesh's decimater).
//
// One collapse sequence is chosen for the rest pose and every example at once: the error of a
// collapse is the sum over all poses of the quadric error (Garland-Heckbert) at the kept vertex,
// and a collapse that would flip or degenerate a triangle in any pose is refused. Collapses are
// half-edge collapses onto an existing vertex, so the simplified mesh keeps a subset of the
// original vertices: in every pose each kept vertex sits exactly at its original position.
// Locked vertices (the handles) are never removed. Optionally a collapse is also refused when a
// removed vertex would lie farther than a bound from the simplified surface in any pose.
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
                                   // from the simplified triangle it is attached to (an upper
                                   // bound of its distance from the simplified surface)
};

// rest:             the rest mesh (#V vertices, #F triangles, manifold)
// examples:         #E pointers, each to a #V by 3 row-major array of one example pose
// locked:           vertex ids that must remain (each in [0, #V))
// target_triangles: stop when at most this many triangles remain (or no legal collapse is left)
// max_normal_change_degrees: refuse a collapse that turns a triangle's normal by more than
//                   this in any pose
// max_distance:     refuse a collapse that leaves a removed vertex farther than this from the
//                   simplified surface in any pose (infinity: no bound; worst_distance is reported
//                   either way)
// Throws InputError for a non-manifold triangle list, indices out of range or a bad target.
DecimationResult decimate_example_set(const MeshView& rest, const std::vector<const double*>& examples,
                                      const std::vector<int>& locked, int target_triangles,
                                      double max_normal_change_degrees = 60.0,
                                      double max_distance = std::numeric_limits<double>::infinity());

}  // namespace meshik
