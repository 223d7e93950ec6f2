// One evaluation of the reduced energy at given weights: phi(w) = min_x E(x, w), with
//   E(x, w) = sum_j |Q_j(x) - F_j(w)|^2 + kappa |w|^2      (fourth vertices eliminated)
// where the handles' rows of x are fixed at their targets. It blends the features, assembles
// the right-hand sides [G'^T s | G'^T J] of all 3 coordinates (3 (#E + 1) columns, row-major),
// runs the factor's forward solve on all of them (H^T K'^{-1} H = (L^{-1} H)^T (L^{-1} H) needs
// no more) and its backward solve on the 3 columns of x0, and forms the Gauss-Newton system:
//   S delta = g,  S = J^T J - H^T K'^{-1} H + kappa I,  g = H^T x0 - J^T s - kappa w,
// with H = G'^T J, s = F(w) - (handles' part of Q) and x0 = K'^{-1} G'^T s (DESIGN.md section 2).
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "blend_regions.h"
#include "example_set_impl.h"
#include "page_arrays.h"
#include "pose_system.h"

namespace meshik {

// Below, K is the number of weights: #E, or #regions by #E (region-major) with BlendRegions.
struct PoseEvaluation {
  std::vector<double> weights;   // K: the weights w evaluated
  std::vector<double> vertices;  // #V by 3: x*(w), handles at their targets
  double energy = 0.0;           // phi(w), regularization (and region smoothness) included
  // Ascending internal indices of the triangles of x*(w) turned over against their targets
  // F_j(w) (normals at more than 90 degrees; see batch_residual).
  std::vector<int> inverted_triangles;
  Eigen::MatrixXd schur;         // K by K: S (only with the Jacobian)
  Eigen::VectorXd step_rhs;      // K: g = -(1/2) d phi / dw (only with the Jacobian)
  // K by K: -sum_j <R_j, d2F_j/dw dw>, so that S + second_order is half the Hessian of phi
  // (zero in the linear space); only once PoseEvaluator::add_second_order has run.
  Eigen::MatrixXd second_order;
  bool has_second_order = false;
  unsigned long evaluation = 0;  // its number among its evaluator's evaluations (from 1)
};

// The evaluator's large arrays, kept between solves (sized on first use) so that a solve neither
// allocates nor page-faults them again.
struct EvaluationBuffers {
  PageArray<double> residual;  // #batches by 6 by kLanes: F_j(w), then R_j = Q_j(x) - F_j(w)
  // PoseSystem::num_rows() + AssemblyPartition::num_extra_rows() rows of 3 (K + 1) doubles
  // rounded up to whole blocks of kLanes, from the first 64-byte boundary: the right-hand sides,
  // then their solution, and the chunks' extra rows (layout: PoseEvaluator's rhs_).
  PageArray<double> rhs;
};

class PoseEvaluator {
 public:
  // set / system: the example set and the factored system of its handles (both outlive this);
  // targets: #H by 3 handle positions; regularization: kappa >= 0; buffers: storage to use (may be
  // shared by successive evaluators, not by simultaneous ones); team: threads of the passes (a
  // thread_count; every result is the same bits for any team: the passes run over the system's
  // fixed partition and combine its chunks in order). blend: how the stretches combine; regions:
  // spatially varying weights (outlives this), or nullptr for one weight vector (K = #E).
  // features: the examples to blend instead of set.features (outlives this; e.g. with_rest_example's),
  // or nullptr; #E is their count.
  PoseEvaluator(const ExampleSet::Impl& set, const PoseSystem& system, FeatureSpace space,
                double regularization, const double* targets, EvaluationBuffers& buffers, int team = 1,
                Blend blend = Blend::kAffine, const BlendRegions* regions = nullptr,
                const ExampleFeatures* features = nullptr);

  // K: the number of weights an evaluation takes.
  int num_weights() const { return num_weights_; }


  // Evaluates at weights (K). with_jacobian = false computes only weights, vertices and energy.
  void evaluate(const double* weights, bool with_jacobian, PoseEvaluation& out);

  // Only the Gauss-Newton system at weights (K), in two halves: the assembly, which reads the
  // system's rows, coupling and partition but not its factor (so it may run while the system is
  // factored), then, once it is factored, the rest with the same weights, filling out.weights,
  // out.schur and out.step_rhs (no pose, energy or backward solve; out.evaluation = 0, so
  // add_second_order refuses it).
  void assemble_system(const double* weights);
  void solve_assembled_system(const double* weights, PoseEvaluation& out);
  // The threads of the passes from now on (a thread_count; the same bits for any team).
  void set_team(int team) { team_ = team; }
  // After solve_assembled_system: finishes the solve of the Jacobian's columns on the system rows `rows`
  // (factor order) only, along their elimination-tree paths.
  void solve_jacobian_rows(const std::vector<int>& rows);
  // Then, for those rows u: K values of Z = K'^{-1} G'^T J for coordinate c.
  const double* jacobian_solution(int unknown, int c) const {
    return rhs_ + static_cast<size_t>(unknown) * stride_ + 3 + c * num_weights_;
  }

  // Fills at.second_order for the pose this evaluator evaluated last (one more pass over the
  // triangles, re-blending them and reusing that evaluation's residuals; only worth it when a
  // step is taken from `at`). Throws std::logic_error for any other pose.
  void add_second_order(PoseEvaluation& at);

 private:
  // Blends every batch of triangles, stores F_j(w), accumulates J^T J and J^T s, and scatters
  // G'^T s and G'^T J into rhs_ (rows of stride_ doubles): the partition's chunks in parallel,
  // then their extra rows and sums in chunk order.
  void assemble(const double* weights, bool with_jacobian);
  // assemble()'s work on one chunk: its batches' F_j(w) into residual_, its sums into its slices
  // of jtj_lanes_, jts_lanes_ and handle_jts_, its scatter into its rows of rhs_.
  // source: column_sources for stride_ (unused with regions).
  void assemble_chunk(const double* weights, bool with_jacobian, const int* source, int chunk);
  // With regions: blends one batch at the region weights (K) into batch_out_'s slice of the chunk
  // and writes region_out (1 + #active #E blocks of 6 rows of kLanes: F_j, then alpha_jr dF_j/dw_i
  // for the batch's active regions r in order) and its columns' indices among the K weights
  // (columns) and rhs sources (source, stride_ entries). Returns the number of Jacobian columns.
  int blend_region_batch(const double* weights, bool with_jacobian, int batch, int chunk, double* region_out,
                         int* columns, int* source);
  // With regions: add_second_order's per-chunk pass (pairs of batches) into curvature_lanes_
  // (batches wholly inside one region, as without regions, into that region's diagonal block) and
  // region_curvature_ (the others, per triangle).
  void add_region_curvature(const double* weights, int chunk);
  // The triangle-varying weights of `lanes` triangles from first (internal order) at the region
  // weights (K): #E rows of `row` doubles, zero beyond lanes.
  void lane_weights(const double* weights, int first, int lanes, int row, double* out) const;
  // More than one region: J^T J is block sparse, each chunk's only in its regions' blocks.
  bool several_regions() const { return regions_ != nullptr && regions_->num_regions > 1; }
  // Calls visit(a, b) for the entries b <= a of J^T J (K by K) in the blocks of pairs of regions
  // that chunk carries (chunk_regions_), region pair by region pair.
  void for_chunk_region_blocks(int chunk, const std::function<void(int, int)>& visit) const;
  // With several regions: jtj_ from the chunks' blocks of jtj_lanes_ (lanes, then chunks in order).
  void sum_region_blocks();
  // per_chunk: #chunks slices of `size` doubles; adds slices 1.. to slice 0, in chunk order.
  void sum_chunks(std::vector<double>& per_chunk, int size) const;
  // From the forward-solved rhs_: hth += H^T K'^{-1} H (K by K) and htx += H^T x0 (K), all K
  // columns in every row (global_products) or only the regions each row carries (region_products,
  // with more than one region; region_outer_products.h).
  void global_products(Eigen::MatrixXd& hth, Eigen::VectorXd& htx);
  void region_products(Eigen::MatrixXd& hth, Eigen::VectorXd& htx);
  // assemble(), the forward solve, and with the Jacobian the Gauss-Newton system (out.weights,
  // out.schur, out.step_rhs).
  void assemble_and_forward_solve(const double* weights, bool with_jacobian, PoseEvaluation& out);
  // assemble_and_forward_solve after its assemble() (stride_ set for with_jacobian).
  void forward_solve_assembled(const double* weights, bool with_jacobian, PoseEvaluation& out);
  // Writes x*(w) (#V by 3) from the solved rhs_ and the targets: a work-shared loop, called
  // inside a parallel region.
  void gather_vertices(double* vertices) const;
  // The region smoothness W^T (M kron I) W at weights (K), and with product its gradient's half
  // (M kron I) W (K values); zero without regions or with one.
  double region_smoothness_energy(const double* weights, Eigen::VectorXd* product) const;
  // One chunk's part of sum_j |Q_j(x) - F_j(w)|^2 for vertices x (#V by 3), F from the last
  // assemble(): replaces F by those residuals in residual_, writes the sum to
  // chunk_energy_[chunk] and the triangles turned over against F to chunk_inverted_[chunk].
  void residual_chunk(const double* vertices, int chunk);
  // gather_vertices into vertices (#V by 3), then the residual energy over all chunks (returned)
  // and the ascending triangles turned over against F (inverted).
  double pose_and_residual(double* vertices, std::vector<int>& inverted);

  const ExampleSet::Impl& set_;
  const PoseSystem& system_;
  const AssemblyPartition& partition_;
  FeatureSpace space_;
  Blend blend_;
  const BlendRegions* regions_;  // nullptr: one weight vector
  const ExampleFeatures& features_;  // the examples blended: set.features or the constructor's
  int num_examples_;                 // #E: features_.num_examples
  int num_weights_;              // K
  double regularization_;
  const double* targets_;
  int team_;
  std::vector<double> handle_offset_;    // #handle triangles by 6: handles' part of Q_j
  std::vector<char> batch_has_handle_;   // per batch: does it hold a triangle with a handle?
  std::vector<double> batch_out_;        // #chunks by blend_batch_size(#E): a batch's F and dF/dw
  // With regions, per chunk: a batch's region_out (6 (K + 1) kLanes), its columns (K) and rhs
  // sources (row_width(3 (K + 1))), and 2 kLanes lane weights per example.
  std::vector<int> all_columns_;  // 0 .. K - 1: the columns of a batch without regions
  std::vector<double> region_out_;
  std::vector<int> region_columns_;
  std::vector<int> region_source_;
  std::vector<double> region_lane_weights_;
  std::vector<double> region_curvature_;  // #chunks by K by K: the per-triangle curvature sums
  PageArray<double>& residual_;        // buffers' residual
  unsigned long evaluations_ = 0;        // evaluations so far
  // Buffers' rhs, one row of stride_ doubles per unknown (in the factor's order): the 3
  // coordinates of G'^T s, then with the Jacobian coordinate c's K columns of G'^T J at
  // 3 + c K + a; solved in place (x0 in the first 3 columns).
  double* rhs_ = nullptr;
  int stride_ = 0;  // of the last evaluation: 3 or 3 (K + 1) columns rounded up to kLanes
  // Per chunk (#chunks slices each, summed into the first in chunk order):
  std::vector<double> jtj_lanes_;        // K by K by kLanes: J^T J, per lane
  std::vector<double> jts_lanes_;        // K by kLanes: J^T F, per lane
  std::vector<double> handle_jts_;       // K: -J^T (handles' part of Q)
  // #E by #E by kLanes per region (one block without regions): sum <R, d2F>, per lane.
  int curvature_size_;
  std::vector<double> curvature_lanes_;
  std::vector<float> curvature_scratch_;  // curvature_scratch_size(#E): add_residual_curvature's
  std::vector<double> chunk_energy_;     // 1: the chunk's residual energy
  std::vector<std::vector<int>> chunk_inverted_;  // the chunk's inverted triangles
  // Without regions, 3 K by stride_: sum_u (L^{-1} H)_u^T (row u of rhs_); with them K by K + 1
  // (add_region_outer_products).
  std::vector<double> outer_products_;
  std::vector<int> region_active_;       // #regions: the regions a row carries
  std::vector<std::vector<int>> chunk_regions_;  // ascending: the regions of the chunk's batches
  Eigen::MatrixXd jtj_;                  // K by K
  Eigen::VectorXd jts_;                  // K: J^T s
};

}  // namespace meshik
