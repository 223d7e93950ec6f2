#include "sparse/numeric.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "meshik/sparse_cholesky.h"
#include "sparse/dense_kernels.h"
#include "sparse/simplicial_prefix.h"

namespace meshik::sparse {

namespace {

// Adds the lower triangle's columns first .. first+k-1 into the r by k block `block`
// (rows: position[]).
void gather_columns(const Pattern& lower, const double* lower_values, int first, int k, int r,
                    const std::vector<int>& position, double* block) {
  for (int c = 0; c < k; ++c) {
    double* column = block + static_cast<long>(c) * r;
    const int j = first + c;
    for (int p = lower.col_start[j]; p < lower.col_start[j + 1]; ++p)
      column[position[lower.row_index[p]]] += lower_values[p];
  }
}

// A child's update matrix as its parent sees it.
struct ChildUpdate {
  const double* u;        // packed lower, m by m
  int m;
  const int* relative;    // m: the child's update rows as indices in the parent's rows, increasing
};

// Adds column q of the child's update matrix (rows q .. m-1) to dst[relative[p] - shift].
void add_child_column(const ChildUpdate& c, int q, double* dst, int shift) {
  const double* uq = c.u + packed_column_offset(c.m, q) - q;  // uq[p] is U(p, q)
  for (int p = q; p < c.m; ++p) dst[c.relative[p] - shift] += uq[p];
}

// Adds the child's columns q with relative[q] < k (the parent's pivot columns) into the
// parent's r by k block; returns the first other column.
int add_to_pivot_block(const ChildUpdate& c, int k, int r, double* block) {
  int q = 0;
  for (; q < c.m && c.relative[q] < k; ++q) add_child_column(c, q, block + static_cast<long>(c.relative[q]) * r, 0);
  return q;
}

// Adds the child's columns q >= first_q into the parent's own update matrix (packed lower,
// parent_m by parent_m, its rows the parent's rows from k on).
void add_to_update(const ChildUpdate& c, int first_q, int k, double* parent_u, int parent_m) {
  for (int q = first_q; q < c.m; ++q) {
    const int target = c.relative[q] - k;
    add_child_column(c, q, parent_u + packed_column_offset(parent_m, target) - target, k);
  }
}

// Work arrays of one factorization.
struct Workspace {
  std::vector<int> position;            // n: row -> index in the current supernode's rows
  std::vector<int> relative;            // the children's update rows as indices in the parent
  std::vector<ChildUpdate> children;    // the current supernode's children
  std::vector<int> first_update_column; // per child: its first column past the parent's pivots
  std::vector<double> stack;            // update matrices waiting for their parents
  std::vector<size_t> stack_offset;     // #S: where each supernode's update matrix sits
};

}  // namespace

void factorize_numeric(const Analysis& analysis, const std::vector<double>& a_values, FactorValues& factor) {
  const std::vector<int>& source = analysis.lower.source;
  factor.lower_values.resize(source.size());
  for (size_t p = 0; p < source.size(); ++p) factor.lower_values[p] = a_values[source[p]];
  eliminate_prefix(analysis.prefix, factor.lower_values, analysis.perm, factor.prefix_diagonal, factor.prefix_below);
  factorize_supernodal(analysis.symbolic, analysis.lower.pattern, factor.lower_values.data(), analysis.perm,
                       factor.supernodal);
}

void throw_not_positive_definite(int original_column) {
  throw NotPositiveDefinite("SparseCholesky: matrix is not positive definite (pivot of column " +
                            std::to_string(original_column) + " is not positive)");
}

void factorize_supernodal(const SymbolicFactor& f, const Pattern& lower, const double* lower_values,
                          const std::vector<int>& original_column, std::vector<double>& values) {
  const int ns = f.num_supernodes();
  values.resize(f.value_start[ns]);
  Workspace w;
  w.position.resize(f.n);
  w.relative.resize(f.rows.size());  // the children's rows are disjoint parts of f.rows
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
    gather_columns(lower, lower_values, first, k, r, w.position, block);

    // Children's contributions to the pivot columns, before the dense factorization.
    const int* child = f.children.data() + f.child_start[s];
    const int num_children = f.child_start[s + 1] - f.child_start[s];
    w.children.clear();
    w.first_update_column.clear();
    int* relative = w.relative.data();
    for (int c = 0; c < num_children; ++c) {
      const int ch = child[c];
      const int child_k = f.first_column[ch + 1] - f.first_column[ch];
      const int child_m = f.row_start[ch + 1] - f.row_start[ch] - child_k;
      const int* child_rows = f.rows.data() + f.row_start[ch] + child_k;
      for (int q = 0; q < child_m; ++q) relative[q] = w.position[child_rows[q]];
      w.children.push_back({w.stack.data() + w.stack_offset[ch], child_m, relative});
      w.first_update_column.push_back(add_to_pivot_block(w.children.back(), k, r, block));
      relative += child_m;
    }

    const int failed = factor_panel(block, r, k);
    if (failed >= 0) throw_not_positive_definite(original_column[first + failed]);

    // Own update matrix on top of the children's, then the rest of the children's updates.
    double* u = w.stack.data() + top;
    if (m > 0) negative_lower_product(block + k, r, m, k, u);
    for (size_t c = 0; c < w.children.size(); ++c) add_to_update(w.children[c], w.first_update_column[c], k, u, m);
    // Pop the children and move the new update matrix down in their place.
    const size_t base = num_children > 0 ? w.stack_offset[child[0]] : top;
    if (m > 0 && base != top) std::memmove(w.stack.data() + base, u, packed_size(m) * sizeof(double));
    w.stack_offset[s] = base;
    top = base + (m > 0 ? packed_size(m) : 0);
  }
}

}  // namespace meshik::sparse
