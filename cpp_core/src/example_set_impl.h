// What an ExampleSet holds: the rest mesh, its topology and frames, the examples' features, the
// eliminated normal matrix K on all vertices, and the per-component centroids used by blend().
//
// Everything is stored in an internal vertex and triangle order chosen for cache locality
// (locality_order.h); the public API translates vertex indices and positions at its boundary.
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "feature_space.h"
#include "meshik/meshik.h"
#include "meshik/sparse_cholesky.h"
#include "mesh_topology.h"
#include "phase_clock.h"
#include "triangle_frames.h"

namespace meshik {

class PoseSystem;

struct ExampleSet::Impl {
  int num_vertices = 0;
  int num_triangles = 0;
  int num_examples = 0;
  std::vector<int> vertex_of_internal;  // #V: the user's index of each internal vertex
  std::vector<int> internal_of_vertex;  // #V: the internal index of each user vertex
  std::vector<int> triangle_of_internal;  // #F: the user's index of each internal triangle
  std::vector<double> rest;    // #V by 3, internal order
  std::vector<int> triangles;  // #F by 3 internal vertex indices, internal triangle order
  VertexComponents components;
  TriangleFrames frames;  // the in-plane gradients only (the features took the rest)
  ExampleFeatures features;
  // Every handle set's pose system (pose_system.h) has a row for each vertex used by triangles
  // and the pattern of the lower triangle of K (gradient_operator.h) there; built and analysed
  // (ordering, symbolic factorization) once here. K itself is kept only there (symmetric: the
  // handles' columns are read from their rows and columns of the lower triangle).
  std::vector<int> system_row_of_vertex;  // #V: the vertex's row (increasing vertex order), or -1
  SparseCholesky system_analysis;         // the triangle's analysis, its pattern (analyzed_pattern())
  std::vector<double> system_values;      // the triangle's values, one per entry of that pattern
  // Per component c: the rest centroid (3) and each example's centroid minus it (#E by 3), so
  // that the linear blend's centroid is rest_centroid[c] + sum_i w_i centroid_shift[c][i].
  std::vector<double> rest_centroid;   // #components by 3
  std::vector<double> centroid_shift;  // #components by #E by 3
  PhaseTimes phase_times;  // the constructor's phases (for benchmarks)

  // blend() solves with one anchor vertex per component; built on first use.
  mutable std::once_flag blend_system_once;
  mutable std::unique_ptr<PoseSystem> blend_system;

  Impl();
  ~Impl();

  // positions: #V by 3 in the user's vertex order; returns them in the internal order.
  std::vector<double> to_internal(const double* positions) const;
  // to_internal into `internal` (#V by 3, every entry written).
  void to_internal(const double* positions, double* internal) const;
  // positions: #V by 3 in the internal order; returns them in the user's vertex order.
  std::vector<double> to_user(const std::vector<double>& positions) const;
};

}  // namespace meshik
