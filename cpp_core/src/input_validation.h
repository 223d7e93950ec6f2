// Checks of the user's input; each throws InputError with a message naming the bad element.
#pragma once

#include <vector>

#include "meshik/meshik.h"
#include "mesh_topology.h"

namespace meshik {

// The rest mesh: at least one vertex and triangle, finite coordinates, triangle indices in range
// and distinct within a triangle, and no triangle of (numerically) zero area.
void validate_rest_mesh(const MeshView& rest);

// Each example is non-null with #V finite vertex positions (#V by 3 row-major).
void validate_examples(const std::vector<const double*>& examples, int num_vertices);

// handles: #H distinct vertex indices in [0, num_vertices), at least one, and at least one in
// every connected component of the triangles. components: over internal vertex indices, which
// internal_of_vertex (#V) gives for the user's (messages name the user's indices).
void validate_handles(const std::vector<int>& handles, int num_vertices,
                      const VertexComponents& components, const std::vector<int>& internal_of_vertex);

// Options of the solver: finite non-negative regularization, tolerance and region smoothness,
// max_iterations >= 0, regions >= 1 or kAutomaticRegions.
void validate_options(const SolverOptions& options);

// values: count finite numbers; what names the array in the message ("initial weight", ...).
void validate_finite(const double* values, int count, const char* what);

// targets: #H by 3 row-major finite positions of the handles.
void validate_targets(const double* targets, const std::vector<int>& handles);

// Throws InputError unless the pose of a solve is finite: result.vertices (#V by 3), its weights
// and its residual. The message names the handle whose target lies farthest out (targets: #H by 3,
// handles: #H vertex indices), the likely cause: targets so large that the solve overflows.
void validate_pose_finite(const SolveResult& result, const double* targets, const std::vector<int>& handles);

}  // namespace meshik
