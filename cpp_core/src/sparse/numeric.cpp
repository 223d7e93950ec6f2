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
  size_t top = 0;                       // end of the stack's used part
};

// Supernode s of the factor: k columns from `first`, r rows, m = r - k below its diagonal
// block, and its r by k column-major block of values.
struct Supernode {
  int first, k, r, m;
  const int* rows;
  double* block;
};

// Returns supernode s of f, its block in `values`.
Supernode supernode(const SymbolicFactor& f, std::vector<double>& values, int s) {
  const int k = f.first_column[s + 1] - f.first_column[s];
  const int r = f.row_start[s + 1] - f.row_start[s];
  return {f.first_column[s], k, r, r - k, f.rows.data() + f.row_start[s], values.data() + f.value_start[s]};
}

// Fills the block of supernode s with A's columns and the children's contributions to its
// pivot columns; records the children (w.children, w.first_update_column) for push_update.
void assemble_block(const SymbolicFactor& f, int s, const Supernode& node, const Pattern& lower,
                    const double* lower_values, Workspace& w) {
  for (int i = 0; i < node.r; ++i) w.position[node.rows[i]] = i;
  std::fill(node.block, node.block + static_cast<long>(node.r) * node.k, 0.0);
  gather_columns(lower, lower_values, node.first, node.k, node.r, w.position, node.block);
  w.children.clear();
  w.first_update_column.clear();
  int* relative = w.relative.data();
  for (int c = f.child_start[s]; c < f.child_start[s + 1]; ++c) {
    const int child = f.children[c];
    const int child_k = f.first_column[child + 1] - f.first_column[child];
    const int child_m = f.row_start[child + 1] - f.row_start[child] - child_k;
    const int* child_rows = f.rows.data() + f.row_start[child] + child_k;
    for (int q = 0; q < child_m; ++q) relative[q] = w.position[child_rows[q]];
    w.children.push_back({w.stack.data() + w.stack_offset[child], child_m, relative});
    w.first_update_column.push_back(add_to_pivot_block(w.children.back(), node.k, node.r, node.block));
    relative += child_m;
  }
}

// After the block of supernode s is factored: builds its update matrix -L21 L21^T plus the
// rest of its children's updates on top of the stack, then moves it down over the children's
// (which are on top of the stack, the first child lowest).
void push_update(const SymbolicFactor& f, int s, const Supernode& node, Workspace& w) {
  double* u = w.stack.data() + w.top;
  if (node.m > 0) negative_lower_product(node.block + node.k, node.r, node.m, node.k, u);
  for (size_t c = 0; c < w.children.size(); ++c)
    add_to_update(w.children[c], w.first_update_column[c], node.k, u, node.m);
  const bool has_children = f.child_start[s + 1] > f.child_start[s];
  const size_t base = has_children ? w.stack_offset[f.children[f.child_start[s]]] : w.top;
  const size_t size = node.m > 0 ? packed_size(node.m) : 0;
  if (size > 0 && base != w.top) std::memmove(w.stack.data() + base, u, size * sizeof(double));
  w.stack_offset[s] = base;
  w.top = base + size;
}

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
  w.relative.resize(f.rows.size());  // each child's rows are a distinct part of f.rows
  w.stack.resize(f.stack_size);
  w.stack_offset.resize(ns);
  for (int s = 0; s < ns; ++s) {
    const Supernode node = supernode(f, values, s);
    assemble_block(f, s, node, lower, lower_values, w);
    const int failed = factor_panel(node.block, node.r, node.k);
    if (failed >= 0) throw_not_positive_definite(original_column[node.first + failed]);
    push_update(f, s, node, w);
  }
}

}  // namespace meshik::sparse
