// The factored normal matrix of one handle set: K' = G'^T G' on the free vertices (fourth
// vertices eliminated, handles' columns taken out), the coupling K_fh that moves the handles'
// contribution to the right-hand side, and the maps between vertices and unknowns.
//
// Built once per handle set; moving the handles only changes right-hand sides. The system keeps a
// row for every vertex used by triangles, handles included, with identity rows and columns for
// the handles: every handle set's matrix then has the mesh's pattern, analysed once by the
// ExampleSet, and only its values are factored here; a handle's row of every solution is zero.
// The rows are numbered in the factor's order, so right-hand sides are solved in place, without
// a permuted copy.
#pragma once

#include <functional>
#include <vector>

#include "assembly_partition.h"
#include "meshik/meshik.h"
#include "meshik/sparse_cholesky.h"

namespace meshik {

class PoseSystem {
 public:
  // set: the validated example set; handles: validated distinct vertex indices (every component
  // of the triangles holds one); team: threads of the factorization (a thread_count; the same
  // bits for any team); handle_stiffness: 0 for hard handles, > 0 for soft ones (soft_handles.h:
  // the handles keep their rows, K' gains their pull, and the coupling is that pull).
  // Assembles K' and factors it on the set's analysis. beside_factorization (optional) is called
  // with this system once everything but the factor is set (rows, coupling, handle triangles,
  // partition): with team > 1 on a thread of its own (which also numbers the rows and builds the
  // partition) while the team factors, else before; it must not use the factor. What it throws
  // is thrown here, after the factorization.
  PoseSystem(const ExampleSet::Impl& set, const std::vector<int>& handles,
             const ProgressCallback& progress = {}, int team = 1, double handle_stiffness = 0.0,
             const std::function<void(const PoseSystem&)>& beside_factorization = {});

  // #V: the row of each free vertex (an unknown of K'), or -1 for a handle or a vertex used by
  // no triangle.
  const std::vector<int>& unknown_of_vertex() const { return unknown_of_vertex_; }
  // Rows of the factored system: the free vertices' and the handles' (whose are always zero).
  int num_rows() const { return num_rows_; }
  const std::vector<int>& handles() const { return handles_; }
  // #V: the index in handles() of each vertex fixed at its target (every handle when hard; with
  // soft handles only those used by no triangle), or -1.
  const std::vector<int>& handle_of_vertex() const { return handle_of_vertex_; }
  // The soft handles' penalty sum_h sigma_h |x_h - t_h|^2 for vertices (#V by 3) and targets
  // (#H by 3); 0 with hard handles.
  double soft_handle_energy(const double* vertices, const double* targets) const;

  // Triangles with at least one handle corner, and for each #F triangle its index in that list
  // (or -1).
  const std::vector<int>& handle_triangles() const { return handle_triangles_; }
  const std::vector<int>& handle_triangle_slot() const { return handle_triangle_slot_; }

  // Subtracts K_fh x_h, the handles' coupling to the free vertices for handle positions targets
  // (#H by 3, row-major), from the first 3 columns of rows (num_rows() rows of `stride` doubles):
  // only the rows coupled to a handle change, by handle and entry in order.
  void subtract_handle_coupling(const double* targets, double* rows, int stride) const;

  // K_fh by handle h: rows coupling_row()[s] and values coupling_value()[s] of the unknowns
  // coupled to handle h, for s in [coupling_start()[h], coupling_start()[h + 1]).
  const std::vector<int>& coupling_start() const { return coupling_start_; }
  const std::vector<int>& coupling_row() const { return coupling_row_; }
  const std::vector<double>& coupling_value() const { return coupling_value_; }

  // The in-place halves of the solve with the factored system (rows in the factor's order):
  // x is num_rows() rows of `stride` = padded_width(m) doubles; the first `columns` (rounded up to
  // whole vectors) of every row are overwritten with L^{-1} x (forward) or L^{-T} x (backward).
  // team: threads over subtrees of the elimination tree and groups of columns (the same bits for
  // any team).
  static int padded_width(int nrhs) { return SparseCholesky::padded_width(nrhs); }
  void forward_solve(double* x, int stride, int columns, int team = 1) const {
    if (num_rows_ > 0) factor_.forward_solve_in_order(x, stride, columns, team);
  }
  void backward_solve(double* x, int stride, int columns, int team = 1) const {
    if (num_rows_ > 0) factor_.backward_solve_in_order(x, stride, columns, team);
  }
  // backward_solve exact on the rows `rows` only (SparseCholesky::backward_solve_rows_in_order).
  void backward_solve_rows(double* x, int stride, int columns, const std::vector<int>& rows, int team = 1) const {
    if (num_rows_ > 0) factor_.backward_solve_rows_in_order(x, stride, columns, rows, team);
  }

  // The triangles' fixed chunks for the evaluation passes and the rows their corners scatter to.
  const AssemblyPartition& partition() const { return partition_; }

  long long factor_nonzeros() const { return factor_.factor_nonzeros(); }

 private:
  // Renumbers unknown_of_vertex_ and coupling_row_ in the factor's row order (after factoring).
  void number_rows_in_factor_order();

  std::vector<int> handles_;
  std::vector<int> handle_of_vertex_;
  std::vector<int> unknown_of_vertex_;
  int num_rows_ = 0;
  // K_fh by handle: entries coupling_row_[s], coupling_value_[s] for s in
  // [coupling_start_[h], coupling_start_[h+1]).
  std::vector<int> coupling_start_;
  std::vector<int> coupling_row_;
  std::vector<double> coupling_value_;
  std::vector<int> handle_triangles_;
  std::vector<int> handle_triangle_slot_;
  std::vector<double> soft_pull_;  // #H: sigma_h of soft handles; empty when hard
  SparseCholesky factor_;
  AssemblyPartition partition_;
};

}  // namespace meshik
