// Assembly of K' and K_fh for a handle set, and its sparse Cholesky factorization.
#include "pose_system.h"

#include <algorithm>
#include <future>
#include <string>
#include <utility>

#include "example_set_impl.h"
#include "heap_release.h"
#include "soft_handles.h"

namespace meshik {

namespace {

// Takes the handles out of the lower triangle of K (pattern `lower` on the system's rows, its
// values in `values`): their rows and columns become identity in `values`, and what they held off
// the diagonal is K_fh. Handle h's column of K is its row left of the diagonal (one entry in each
// earlier column) followed by its own column below it, so one pass over the columns lists each
// handle's free rows in increasing order. handle_of_row: the handle at each row, or -1.
// Fills row (the free rows) and value (K's entries there), and returns num_handles + 1 offsets
// into them.
std::vector<int> take_out_handles(const CscMatrix& lower, std::vector<double>& values,
                                  const std::vector<int>& handle_of_row, int num_handles, std::vector<int>& row,
                                  std::vector<double>& value) {
  std::vector<std::vector<std::pair<int, double>>> coupled(num_handles);
  for (int col = 0; col < lower.cols; ++col)
    for (int s = lower.col_start[col]; s < lower.col_start[col + 1]; ++s) {
      const int r = lower.row_index[s];
      const int h_row = handle_of_row[r], h_col = handle_of_row[col];
      if (h_row < 0 && h_col < 0) continue;
      if (h_row < 0 || h_col < 0) coupled[h_row >= 0 ? h_row : h_col].emplace_back(h_row >= 0 ? col : r, values[s]);
      values[s] = r == col ? 1.0 : 0.0;
    }
  std::vector<int> start(1, 0);
  for (const auto& entries : coupled) {
    for (const auto& [r, v] : entries) {
      row.push_back(r);
      value.push_back(v);
    }
    start.push_back(static_cast<int>(row.size()));
  }
  return start;
}

}  // namespace

PoseSystem::PoseSystem(const ExampleSet::Impl& set, const std::vector<int>& handles,
                       const ProgressCallback& progress, int team, double handle_stiffness,
                       const std::function<void(const PoseSystem&)>& beside_factorization)
    : handles_(handles) {
  const int n = set.num_vertices;
  handle_of_vertex_.assign(n, -1);
  for (size_t h = 0; h < handles.size(); ++h) handle_of_vertex_[handles[h]] = static_cast<int>(h);
  unknown_of_vertex_ = set.system_row_of_vertex;
  // K' and the handles' identity rows and columns: values on the mesh's pattern.
  const CscMatrix& lower = set.system_analysis.analyzed_pattern();
  num_rows_ = lower.rows;
  std::vector<int> handle_of_row(num_rows_, -1);
  for (size_t h = 0; h < handles.size(); ++h)
    if (unknown_of_vertex_[handles[h]] >= 0) handle_of_row[unknown_of_vertex_[handles[h]]] = static_cast<int>(h);
  std::vector<double> values = set.system_values;
  if (handle_stiffness > 0.0) {
    coupling_start_ = pull_handles_softly(lower, values, handle_of_row, static_cast<int>(handles.size()),
                                          handle_stiffness, coupling_row_, coupling_value_, soft_pull_);
    // Only a handle used by no triangle (no row) stays fixed at its target.
    for (int v : handles)
      if (unknown_of_vertex_[v] >= 0) handle_of_vertex_[v] = -1;
  } else {
    coupling_start_ = take_out_handles(lower, values, handle_of_row, static_cast<int>(handles.size()),
                                       coupling_row_, coupling_value_);
    for (int v : handles) unknown_of_vertex_[v] = -1;
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
  if (num_rows_ > 0) factor_.share_analysis(set.system_analysis);
  // What the factorization does not need: the rows in the factor's order (the analysis's), the
  // partition, then beside_factorization. With it and team > 1, on a thread of its own while the
  // team factors the values (the future waits for it, also when the factorization throws).
  const auto number_rows = [this, &set, &beside_factorization] {
    number_rows_in_factor_order();
    partition_ = assembly_partition(set.triangles, unknown_of_vertex_, num_rows_);
    if (beside_factorization) beside_factorization(*this);
  };
  std::future<void> beside;
  if (beside_factorization && team > 1)
    beside = std::async(std::launch::async, number_rows);
  else
    number_rows();
  try {
    if (num_rows_ > 0) factor_.factorize_values(values, team);
  } catch (const NotPositiveDefinite& e) {
    throw InputError(std::string("the mesh's pose system is singular (degenerate geometry): ") +
                     e.what());
  }
  if (beside.valid()) beside.get();
  // The factorization's work arrays (the values' copies, the update stacks) are freed: when large,
  // their pages go back before the poses' own buffers are allocated (heap_release.h).
  release_free_heap_memory();
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

double PoseSystem::soft_handle_energy(const double* vertices, const double* targets) const {
  return meshik::soft_handle_energy(vertices, handles_, targets, soft_pull_);
}

void PoseSystem::subtract_handle_coupling(const double* targets, double* rows, int stride) const {
  for (size_t h = 0; h < handles_.size(); ++h) {
    const double* x = targets + 3 * h;
    for (int s = coupling_start_[h]; s < coupling_start_[h + 1]; ++s) {
      double* row = rows + static_cast<size_t>(coupling_row_[s]) * stride;
      const double value = coupling_value_[s];
      row[0] -= value * x[0];
      row[1] -= value * x[1];
      row[2] -= value * x[2];
    }
  }
}

}  // namespace meshik
