// The examples' per-triangle features and their blend M(w) with its exact Jacobian dM/dw.
//
// Only T_j(w) U_j (3 by 2) enters the eliminated energy (triangle_frames.h), so the features are
// stored projected on the rest plane:
//   nonlinear: phi_ij = log R_ij (a consistent branch), D_ij = (S_ij - I) U_j
//              F_j(w) = exp(sum_i w_i phi_ij) (U_j + sum_i w_i D_ij)
//   linear:    L_ij = (T_ij - I) U_j,     F_j(w) = U_j + sum_i w_i L_ij
// with T_ij = R_ij S_ij the proper polar decomposition. w = 0 gives U_j (the rest pose) and
// w = e_i gives T_ij U_j (example i). Only the nonlinear features are stored: the linear ones are
// derived from them where read, L_ij = exp(phi_ij) (D_ij + U_j) - U_j (T_ij U_j = R_ij S_ij U_j),
// which keeps 6 of every 15 values per triangle and example out of memory.
//
// Triangles are processed in batches of kLanes, stored lane-minor (structure of arrays per batch)
// so that one batch's arithmetic is SIMD; the last batch is padded with zero features.
#pragma once

#include <functional>
#include <type_traits>
#include <vector>

#include "meshik/meshik.h"
#include "mesh_topology.h"
#include "page_arrays.h"
#include "triangle_frames.h"

namespace meshik {

// Triangles blended together (one AVX-512 register of doubles per quantity).
constexpr int kLanes = 8;

// Batches add_residual_curvature takes at once (16 triangles: one AVX-512 register of floats
// per quantity).
constexpr int kCurvatureBatches = 2;

// The per-example feature values, stored as Stored (float or double; FeaturePrecision).
template <typename Stored>
struct FeatureValues {
  using Value = Stored;
  // Batch b, example i: 9 rows of kLanes values, phi_ij (3) then D_ij (3 by 2 row-major):
  // entry ((b #E + i) 9 + row) kLanes + lane for triangle j = b kLanes + lane.
  PageArray<Stored> nonlinear;
};

// Mixed precision, by the rule of issue 13: "Mixed precision is allowed wherever the pose, energy
// and gradient stay double, the examples still reproduce to < 1e-6 of the bounding-box diagonal,
// and hold-out errors stay within 1e-4 relative of the double-precision result (show it in a
// test)." With FeaturePrecision::kSingle the values are rounded to floats once, when written, and
// every reader widens them to double before any arithmetic (blend_batch, the linear start);
// only add_residual_curvature, which shapes the step and never the energy, computes in float.
// tests/cpp/test_meshik_feature_precision.cpp shows the rule on the horse.
struct ExampleFeatures {
  int num_examples = 0;
  int num_triangles = 0;
  int num_batches = 0;  // ceil(#F / kLanes)
  FeaturePrecision precision = FeaturePrecision::kSingle;
  FeatureValues<float> single;  // the values when precision is kSingle (empty otherwise)
  FeatureValues<double> full;   // the values when precision is kDouble (empty otherwise)
  // Batch b: 6 rows of kLanes, U_j (3 by 2 row-major): (b 6 + row) kLanes + lane.
  PageArray<double> plane_basis;
};

// features.single or features.full (Stored float or double), as the Features' constness.
template <typename Stored, typename Features>
auto& values_of(Features& features) {
  if constexpr (std::is_same_v<Stored, float>)
    return features.single;
  else
    return features.full;
}

// Calls visit(values) with the FeatureValues that `features` holds (its precision's); returns
// what visit returns.
template <typename Features, typename Visit>
decltype(auto) visit_feature_values(Features& features, Visit&& visit) {
  if (features.precision == FeaturePrecision::kSingle) return visit(values_of<float>(features));
  return visit(values_of<double>(features));
}

// frames / adjacency / triangles (#F by 3): the rest mesh's; the features take over the frames'
// plane basis (the in-plane gradients are left). examples: #E pointers to #V by 3 positions.
// consistent_branches = false keeps the principal rotation logs (for comparison only). precision:
// how the values are stored (FeaturePrecision). progress(fraction) is called once per example, on
// the calling thread. threads: 0 = all cores, n = n threads over blocks of triangles (see
// thread_count); the result is identical for any count. threads_free (when set) is asked before
// each parallel pass how many of those threads it may use (1 to the team; the caller's other work
// may hold the rest of the cores).
ExampleFeatures compute_example_features(TriangleFrames& frames,
                                         const TriangleAdjacency& adjacency, const int* triangles,
                                         const std::vector<const double*>& examples,
                                         const ProgressCallback& progress = {},
                                         bool consistent_branches = true, int threads = 0,
                                         FeaturePrecision precision = FeaturePrecision::kSingle,
                                         const std::function<int()>& threads_free = {});

// Number of doubles blend_batch writes: the target and one derivative per example, 6 rows each,
// then room for the batch's features widened to double (9 rows per example).
inline int blend_batch_size(int num_examples) { return (6 * (num_examples + 1) + 9 * num_examples) * kLanes; }

// Blends the triangles of `batch` with weights w (#E). Writes to out (blend_batch_size doubles),
// for q = 0 the targets F_j(w) and for q = 1 .. #E the derivatives dF_j/dw_{q-1}, each 3 by 2
// row-major: out[((q 6) + row) kLanes + lane]; the rest of out is scratch. blend: how the
// stretches combine (meshik.h's Blend): kFree replaces U_j by (sum_i w_i) U_j in F_j and adds
// U_j to each derivative (in both spaces).
void blend_batch(const ExampleFeatures& features, FeatureSpace space, const double* w, int batch,
                 double* out, Blend blend = Blend::kAffine);

// blend_batch with weights that differ per triangle: lane_weights, #E rows of kLanes, example i's
// weight for the triangle in lane l at lane_weights[i kLanes + l].
void blend_batch_lanes(const ExampleFeatures& features, FeatureSpace space, Blend blend, const double* lane_weights,
                       int batch, double* out);

// The linear space's features of example `example` for the triangles of `batch`:
// L_ij = exp(phi_ij) (D_ij + U_j) - U_j, 6 rows of kLanes doubles (3 by 2 row-major) to out, zero
// in padding lanes. The same values blend_batch blends in the linear space.
void linear_features_of_batch(const ExampleFeatures& features, int batch, int example, double* out);

// Floats of scratch add_residual_curvature needs.
inline int curvature_scratch_size(int num_examples) {
  const int k = num_examples;
  return (6 + 9 * k + 6 + 6 * (k + 1) + k * k) * kCurvatureBatches * kLanes;
}

// Nonlinear space only: for the triangles of batches batch (even) and batch + 1 (the second only if it
// exists) blended at w, adds for every pair b <= a of examples <R_j, d2F_j/dw_a dw_b> (symmetric
// in a and b) to curvature_lanes[(a #E + b) kLanes + l] for the triangles in lane l of either
// batch: the second-order term of the energy's Hessian that Gauss-Newton leaves out.
// residual: R_j = Q_j(x) - F_j(w) of the two batches, 6 rows of kLanes each, the second batch's
// after the first's (zero in padding lanes). scratch: curvature_scratch_size floats.
// Computed in single precision: the two batches' features (unless stored as floats already) and
// plane bases are rounded to floats in scratch first. The term only shapes the step (the
// trust-region model), never the energy, its gradient or the pose, so rounding at 1e-7 of its
// size changes no result, while single precision doubles the lanes per instruction.
void add_residual_curvature(const ExampleFeatures& features, const double* w, int batch,
                            const double* residual, float* scratch, double* curvature_lanes,
                            Blend blend = Blend::kAffine);

// add_residual_curvature with weights per triangle and its result per triangle: lane_weights,
// #E rows of kCurvatureBatches kLanes (example i's weight for lane l of the pair, batch's lanes
// first, at lane_weights[i 2 kLanes + l]). Returns, inside scratch, #E #E rows of
// kCurvatureBatches kLanes floats: <R_j, d2F_j/dw_a dw_b> at row a #E + b (b <= a) for each lane.
const float* residual_curvature_lanes(const ExampleFeatures& features, Blend blend, const double* lane_weights,
                                      int batch, const double* residual, float* scratch);

}  // namespace meshik
