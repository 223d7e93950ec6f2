// Assembly of K' and K_fh for a handle set, and its sparse Cholesky factorization.
#include "pose_system.h"

#include <algorithm>
#include <string>

#include "example_set_impl.h"

namespace meshik {

PoseSystem::PoseSystem(const ExampleSet::Impl& set, const std::vector<int>& handles,
                       const ProgressCallback& progress, int team)
    : handles_(handles) {
  const int n = set.num_vertices;
  const CscMatrix& k = set.normal_matrix;
  handle_of_vertex_.assign(n, -1);
  for (size_t h = 0; h < handles.size(); ++h) handle_of_vertex_[handles[h]] = static_cast<int>(h);
  unknown_of_vertex_ = set.system_row_of_vertex;
  // K' and the handles' identity rows and columns, on the mesh's pattern.
  CscMatrix lower = set.system_lower;
  num_rows_ = lower.rows;
  std::vector<char> handle_row(num_rows_, 0);
  for (int v : handles)
    if (unknown_of_vertex_[v] >= 0) handle_row[unknown_of_vertex_[v]] = 1;
  for (int col = 0; col < num_rows_; ++col)
    for (int s = lower.col_start[col]; s < lower.col_start[col + 1]; ++s) {
      const int row = lower.row_index[s];
      if (handle_row[row] || handle_row[col]) lower.values[s] = row == col ? 1.0 : 0.0;
    }
  for (int v : handles) unknown_of_vertex_[v] = -1;

  // K_fh: the handles' columns restricted to the unknowns' rows.
  coupling_start_.assign(1, 0);
  for (int v : handles) {
    for (int s = k.col_start[v]; s < k.col_start[v + 1]; ++s) {
      const int row = unknown_of_vertex_[k.row_index[s]];
      if (row < 0) continue;
      coupling_row_.push_back(row);
      coupling_value_.push_back(k.values[s]);
    }
    coupling_start_.push_back(static_cast<int>(coupling_row_.size()));
  }

  handle_triangle_slot_.assign(set.num_triangles, -1);
  for (int j = 0; j < set.num_triangles; ++j) {
    const int* t = set.triangles.data() + 3 * j;
    if (handle_of_vertex_[t[0]] >= 0 || handle_of_vertex_[t[1]] >= 0 || handle_of_vertex_[t[2]] >= 0) {
      handle_triangle_slot_[j] = static_cast<int>(handle_triangles_.size());
      handle_triangles_.push_back(j);
    }
  }

  if (progress && !progress(0.0, "factorizing"))
    throw Cancelled("cancelled before factorizing");
  try {
    if (num_rows_ > 0) {
      factor_.share_analysis(set.system_analysis);
      factor_.factorize(lower, team);
    }
  } catch (const NotPositiveDefinite& e) {
    throw InputError(std::string("the mesh's pose system is singular (degenerate geometry): ") +
                     e.what());
  }
  number_rows_in_factor_order();
  partition_ = assembly_partition(set.triangles, unknown_of_vertex_, num_rows_);
  if (progress && !progress(1.0, "factorizing")) throw Cancelled("cancelled after factorizing");
}

void PoseSystem::number_rows_in_factor_order() {
  if (num_rows_ == 0) return;
  const std::vector<int>& perm = factor_.permutation();
  std::vector<int> row_of_unknown(num_rows_);
  for (int row = 0; row < num_rows_; ++row) row_of_unknown[perm[row]] = row;
  for (int& u : unknown_of_vertex_)
    if (u >= 0) u = row_of_unknown[u];
  for (int& u : coupling_row_) u = row_of_unknown[u];
}

void PoseSystem::handle_coupling(const double* targets, double* out) const {
  std::fill(out, out + 3 * static_cast<size_t>(num_rows_), 0.0);
  for (size_t h = 0; h < handles_.size(); ++h) {
    const double* x = targets + 3 * h;
    for (int s = coupling_start_[h]; s < coupling_start_[h + 1]; ++s) {
      double* row = out + 3 * static_cast<size_t>(coupling_row_[s]);
      const double value = coupling_value_[s];
      row[0] += value * x[0];
      row[1] += value * x[1];
      row[2] += value * x[2];
    }
  }
}

}  // namespace meshik
