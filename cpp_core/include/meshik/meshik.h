// MeshIK public API: Mesh-Based Inverse Kinematics (Sumner et al. 2005).
//
// The precompute / solve split follows libigl's style:
//   Solver solver(rest, examples, handles, options);   // validates, factors G'^T G' once
//   SolveResult r = solver.solve(targets);              // per frame: Gauss-Newton on (x, w)
//
// All arrays are plain row-major buffers of doubles / ints so that the plugin and the Python
// module can pass their own memory without copies of foreign types. No Eigen, Qt or Python here.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace meshik {

// A triangle mesh viewed, not owned.
//   vertices:  #V by 3 row-major list of vertex positions (x0 y0 z0 x1 y1 z1 ...)
//   triangles: #F by 3 row-major list of 0-based vertex indices
struct MeshView {
  const double* vertices = nullptr;
  int num_vertices = 0;
  const int* triangles = nullptr;
  int num_triangles = 0;
};

// How example deformation gradients are combined.
//   kNonlinear: T_j(w) = exp(sum_i w_i log R_ij) * (I + sum_i w_i (S_ij - I)), T_ij = R_ij S_ij polar.
//   kLinear:    T_j(w) = I + sum_i w_i (T_ij - I).
// In both, w = 0 gives the rest pose and w = e_i gives example i.
enum class FeatureSpace { kNonlinear, kLinear };

// How the examples' stretches S_ij combine in either feature space.
//   kAffine: tied to the rest pose, S_j(w) = I + sum_i w_i (S_ij - I) (the default).
//   kFree:   the paper's own blend, S_j(w) = sum_i w_i S_ij (linear space: sum_i w_i T_ij);
//            w = 0 then collapses every triangle, so use it with weights that sum near one.
//            A Solver's free blend holds the rest pose as example 0, as the paper's feature space
//            does when the rest is one of the examples: S_j(w) = w_0 I + sum_i w_i S_ij (its
//            weights are #E + 1, the rest's first), which contains the affine blend.
// Both reproduce every example at w = e_i; the Jacobians are exact in both.
enum class Blend { kAffine, kFree };

// SolverOptions::regions: the count chosen from the examples (the smallest number of clusters of
// the triangles' deformations, 2 to 8, that explains 80 % of their spread).
constexpr int kAutomaticRegions = -1;

// How an ExampleSet stores the examples' per-triangle features (the rotation logs and projected
// stretches, and the linear space's gradients: 15 values per triangle and example).
//   kSingle: 4-byte floats, 60 bytes per triangle and example. Only the storage is single: every
//            blend, energy, gradient and pose is computed in double from the widened values; the
//            examples reproduce to well within 1e-6 of the bounding-box diagonal (about 1e-9 on
//            the horse) and held-out poses move by about 1e-9 relative.
//   kDouble: 8-byte doubles, 120 bytes per triangle and example (for comparison).
enum class FeaturePrecision { kSingle, kDouble };

struct SolverOptions {
  FeatureSpace feature_space = FeatureSpace::kNonlinear;
  // k in the energy ||G'x - (M(w) + c)||^2 + k ||w||^2 (pulls the pose towards the rest pose).
  double weight_regularization = 0.0;
  // Gauss-Newton stops after this many iterations ...
  int max_iterations = 30;
  // ... or when the relative energy decrease of an iteration falls below this.
  double tolerance = 1e-10;
  // Threads of each solve's passes (blend and scatter, residual, second-order term, outer
  // products, and the triangular solves by groups of columns): 0 = all cores (OpenMP's default
  // team, OMP_NUM_THREADS), n >= 1 = n threads. The result is the same bits for any count (the
  // passes run over a fixed partition of the triangles and combine it in order). A solve called
  // from inside an OpenMP parallel region runs serially (no nested teams); solves called from
  // several threads of the caller at once each start their own team: give each
  // threads = cores / callers (e.g. 1 in a pool of one worker per core).
  int threads = 0;
  // How the stretches combine (Blend).
  Blend blend = Blend::kAffine;
  // Spatially varying weights: one weight vector per region of the surface, blended across the
  // regions' borders (a partition of unity over the triangles), so that legs can take one
  // example's stride and the body another's. 1 = one weight vector for the whole mesh (today's
  // solve); n >= 2 = n regions clustered from how the triangles deform across the examples;
  // kAutomaticRegions = the count chosen from the examples. Ignored when vertex_regions is given.
  int regions = 1;
  // Regions given by the user: #V region ids (0 .. count - 1), or -1 for a vertex in no group
  // (those form one more region); empty = none. A triangle belongs to its corners' regions in
  // proportion.
  std::vector<int> vertex_regions;
  // Strength of the pull between neighbouring regions' weights: the energy gains
  // region_smoothness sum over edges (j, j') of |w_j - w_j'|^2 (w_j: triangle j's blended
  // weights), which makes the weights one global vector where the handles do not say otherwise.
  // 0.01: the best of 0, 0.001, 0.01, 1 and 100 on the horse's held-out gallop (bench_holdout).
  double region_smoothness = 0.01;
  // 0: hard handles, each vertex exactly at its target. > 0: soft handles, each pulled towards its
  // target by handle_stiffness * d_h |x_h - t_h|^2 in the energy (d_h: the vertex's diagonal entry
  // of G'^T G', so the value is scale-free; a handle used by no triangle stays at its target): a
  // target the examples cannot reach then bends the region around the handle instead of pulling
  // that one vertex into a spike. Large values approach the hard pose, small ones leave the
  // examples' pose nearly untouched. Every component still needs a handle.
  double handle_stiffness = 0.0;
};

// Result of one solve.
struct SolveResult {
  std::vector<double> vertices;  // #V by 3 row-major posed vertex positions
  std::vector<double> weights;   // Solver::num_weights() blend weights (#regions by #examples, region-major)
  int iterations = 0;            // Gauss-Newton iterations taken
  double residual = 0.0;         // final energy ||G'x - (M(w) + c)||^2 + k ||w||^2
  bool converged = false;        // stopped by the tolerance rather than max_iterations
  std::vector<double> energies;  // energy at the start and after each accepted iteration
                                 // (non-increasing; the last equals residual)
  // Ascending indices of the triangles that the pose turns over against the orientation their
  // blended deformation asks for (the posed triangle's normal at more than 90 degrees from its
  // target's): folds, typically beside a handle dragged where the examples' space cannot follow.
  // Empty for every example reproduced from its own handles.
  std::vector<int> inverted_triangles;
};

// Called with a fraction in [0, 1] and a short stage name; return false to cancel
// (the running call then throws Cancelled).
using ProgressCallback = std::function<bool(double fraction, const std::string& stage)>;

// Bad input. The message names the element: "triangle 812 has zero area in the rest mesh",
// "example 2 vertex 17 has a non-finite coordinate", "handle 3 (vertex 9001) is out of range".
class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The user cancelled through the progress callback.
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The rest mesh and #E example poses, validated, with their per-triangle features precomputed.
// Shared (read-only) by Solver instances that differ only in their handle sets.
class ExampleSet {
 public:
  // rest:     the rest mesh (#V vertices, #F triangles)
  // examples: #E pointers, each to a #V by 3 row-major array (same vertex order and triangles as rest)
  // threads:  0 = all cores (OpenMP's default team, OMP_NUM_THREADS), n >= 1 = n threads for the
  //           per-triangle passes (with more than one, the serial analysis of the pose systems'
  //           pattern runs beside them); the result is the same bits for any count. Called from
  //           inside an OpenMP parallel region it runs serially (no nested teams, no
  //           oversubscription); called from several threads of the caller at once, each call has
  //           its own team: give each threads = cores / callers.
  // precision: how the features are stored (FeaturePrecision).
  // Throws InputError on any invalid element.
  // Precomputes what both feature spaces need (T_ij, and R_ij, log R_ij, S_ij).
  ExampleSet(const MeshView& rest, const std::vector<const double*>& examples,
             const ProgressCallback& progress = {}, int threads = 0,
             FeaturePrecision precision = FeaturePrecision::kSingle);
  ~ExampleSet();
  ExampleSet(ExampleSet&&) noexcept;
  ExampleSet& operator=(ExampleSet&&) noexcept;

  int num_vertices() const;
  int num_triangles() const;
  int num_examples() const;
  FeaturePrecision feature_precision() const;

  // The combination of the examples with the given weights, no handles.
  //   weights: #E values
  // Returns #V by 3 row-major positions; translation fixed so that the centroid equals the
  // centroid of the linearly blended vertex positions rest + sum_i w_i (example_i - rest).
  std::vector<double> blend(const double* weights,
                            FeatureSpace feature_space = FeatureSpace::kNonlinear,
                            Blend blend = Blend::kAffine) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

class Solver {
 public:
  // examples: a shared, validated example set (kept alive by the solver)
  // handles:  #H distinct vertex indices constrained by solve()
  // Factors G'^T G' once (and solves once for what the linear feature space needs per handle
  // set); throws InputError (no handle, handle out of range or repeated, a connected component
  // without a handle). solve() may be called from several threads at once.
  Solver(std::shared_ptr<const ExampleSet> examples, const std::vector<int>& handles,
         const SolverOptions& options = {}, const ProgressCallback& progress = {});
  ~Solver();
  Solver(Solver&&) noexcept;
  Solver& operator=(Solver&&) noexcept;

  // targets:         #H by 3 row-major target positions, in the order of the handles
  // initial_weights: num_weights() starting weights (warm start, e.g. the previous frame's), or nullptr to
  //                  start from the weights that are optimal in the linear feature space (the
  //                  linear space's solution; for the nonlinear space a better start than the
  //                  rest pose w = 0, which may lie in the basin of a worse local minimum); with
  //                  regions, from the solve without them (every region alike)
  // Never refactors: only the right-hand side changes with the targets.
  SolveResult solve(const double* targets, const double* initial_weights = nullptr,
                    const ProgressCallback& progress = {}) const;

  const ExampleSet& examples() const;
  const std::vector<int>& handles() const;
  const SolverOptions& options() const;
  // The regions of spatially varying weights (1 without them), and the weights a solve takes and
  // returns: #regions by #E, region-major (#E + 1 per region with the free blend: the rest pose's first).
  int num_regions() const;
  int num_weights() const;
  // #F: the region with the largest share of each triangle (all 0 without regions).
  std::vector<int> triangle_regions() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshik
