#include "sparse/numeric.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "meshik/sparse_cholesky.h"
#include "sparse/dense_kernels.h"

namespace meshik::sparse {

namespace {

// Work arrays of one factorization.
struct Workspace {
  std::vector<int> position;            // n: row -> index in the current supernode's rows
  std::vector<int> relative;            // a child's update rows as indices in the parent
  std::vector<double> stack;            // update matrices waiting for their parents
  std::vector<size_t> stack_offset;     // #S: where each supernode's update matrix sits
};

// Adds A's columns first .. first+k-1 into the r by k block `block` (rows: position[]).
void gather_columns(const LowerValues& a, int first, int k, int r, const std::vector<int>& position,
                    double* block) {
  for (int c = 0; c < k; ++c) {
    double* column = block + static_cast<long>(c) * r;
    const int j = first + c;
    for (int p = a.pattern->col_start[j]; p < a.pattern->col_start[j + 1]; ++p)
      column[position[a.pattern->row_index[p]]] += a.values[a.source[p]];
  }
}

// The update matrix `u` of a child (packed lower, m by m) has rows `relative` (m entries,
// increasing) in its parent's numbering. Adds its columns q with relative[q] < k (the parent's
// pivot columns) into the parent's r by k block; returns the first other column.
int add_to_pivot_block(const double* u, int m, const int* relative, int k, int r, double* block) {
  int q = 0;
  for (const double* uq = u; q < m && relative[q] < k; uq += m - q, ++q) {
    double* column = block + static_cast<long>(relative[q]) * r;
    for (int p = q; p < m; ++p) column[relative[p]] += uq[p - q];
  }
  return q;
}

// Adds the columns q >= first_q of a child's update matrix (as above) into the parent's own
// update matrix (packed lower, parent_m by parent_m, rows shifted by the parent's k).
void add_to_update(const double* u, int m, const int* relative, int first_q, int k, double* parent_u,
                   int parent_m) {
  for (int q = first_q; q < m; ++q) {
    const double* uq = u + packed_column_offset(m, q);
    const int target = relative[q] - k;
    double* column = parent_u + packed_column_offset(parent_m, target) - target;
    for (int p = q; p < m; ++p) column[relative[p] - k] += uq[p - q];
  }
}

[[noreturn]] void throw_not_positive_definite(int column) {
  throw NotPositiveDefinite("SparseCholesky: matrix is not positive definite (pivot of column " +
                            std::to_string(column) + " is not positive)");
}

}  // namespace

void factorize_supernodal(const SymbolicFactor& f, const LowerValues& a,
                          const std::vector<int>& original_column, std::vector<double>& values) {
  const int ns = f.num_supernodes();
  values.resize(f.value_start[ns]);
  Workspace w;
  w.position.resize(f.n);
  w.relative.resize(f.n);
  w.stack.resize(f.stack_size);
  w.stack_offset.resize(ns);
  size_t top = 0;
  for (int s = 0; s < ns; ++s) {
    const int first = f.first_column[s];
    const int k = f.first_column[s + 1] - first;
    const int r = f.row_start[s + 1] - f.row_start[s];
    const int m = r - k;
    const int* rows = f.rows.data() + f.row_start[s];
    double* block = values.data() + f.value_start[s];
    for (int i = 0; i < r; ++i) w.position[rows[i]] = i;
    std::fill(block, block + static_cast<long>(r) * k, 0.0);
    gather_columns(a, first, k, r, w.position, block);

    // Children's contributions to the pivot columns, before the dense factorization.
    const int* child = f.children.data() + f.child_start[s];
    const int num_children = f.child_start[s + 1] - f.child_start[s];
    for (int c = 0; c < num_children; ++c) {
      const int ch = child[c];
      const int child_k = f.first_column[ch + 1] - f.first_column[ch];
      const int child_m = f.row_start[ch + 1] - f.row_start[ch] - child_k;
      const int* child_rows = f.rows.data() + f.row_start[ch] + child_k;
      for (int q = 0; q < child_m; ++q) w.relative[q] = w.position[child_rows[q]];
      add_to_pivot_block(w.stack.data() + w.stack_offset[ch], child_m, w.relative.data(), k, r, block);
    }

    const int failed = factor_panel(block, r, k);
    if (failed >= 0) throw_not_positive_definite(original_column[first + failed]);

    // Own update matrix on top of the children's, then the rest of the children's updates.
    double* u = w.stack.data() + top;
    if (m > 0) negative_lower_product(block + k, r, m, k, u);
    for (int c = 0; c < num_children; ++c) {
      const int ch = child[c];
      const int child_k = f.first_column[ch + 1] - f.first_column[ch];
      const int child_m = f.row_start[ch + 1] - f.row_start[ch] - child_k;
      const int* child_rows = f.rows.data() + f.row_start[ch] + child_k;
      for (int q = 0; q < child_m; ++q) w.relative[q] = w.position[child_rows[q]];
      int first_q = 0;
      while (first_q < child_m && w.relative[first_q] < k) ++first_q;
      add_to_update(w.stack.data() + w.stack_offset[ch], child_m, w.relative.data(), first_q, k, u, m);
    }
    // Pop the children and move the new update matrix down in their place.
    const size_t base = num_children > 0 ? w.stack_offset[child[0]] : top;
    if (m > 0 && base != top) std::memmove(w.stack.data() + base, u, packed_size(m) * sizeof(double));
    w.stack_offset[s] = base;
    top = base + (m > 0 ? packed_size(m) : 0);
  }
}

}  // namespace meshik::sparse
