#include "sparse/numeric.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

#include "meshik/sparse_cholesky.h"
#include "page_arrays.h"
#include "sparse/dense_kernels.h"
#include "sparse/simplicial_prefix.h"
#include "thread_count.h"

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

// One thread's work arrays (and the top's): its own multifrontal stack.
struct Workspace {
  std::vector<int> position;            // n: row -> index in the current supernode's rows
  std::vector<int> relative;            // the children's update rows as indices in the parent
  std::vector<ChildUpdate> children;    // the current supernode's children
  std::vector<int> first_update_column; // per child: its first column past the parent's pivots
  std::unique_ptr<double[]> stack;      // update matrices waiting for their parents (each written
                                        // before it is read, so never zeroed)
  size_t top = 0;                       // end of the stack's used part

  // Sizes the arrays for factor f with a stack of `stack_size` doubles; relative_size: the most
  // update rows of one supernode's children together.
  void size_for(const SymbolicFactor& f, size_t stack_size, int relative_size) {
    position.resize(f.n);
    relative.resize(relative_size);
    stack.reset(new double[stack_size]);
    top = 0;
  }
};

// One factorization: the symbolic factor, the matrix, the values being written, and where each
// supernode's update matrix waits (its workspace and offset in that workspace's stack).
struct Multifrontal {
  const SymbolicFactor& f;
  const Pattern& lower;
  const double* lower_values;
  PageArray<double>& values;
  std::vector<Workspace> spaces;
  std::vector<int> owner;           // #S: the workspace holding the supernode's update matrix
  std::vector<size_t> stack_offset; // #S: where in that workspace's stack

  Multifrontal(const SymbolicFactor& factor, const Pattern& matrix, const double* matrix_values,
               PageArray<double>& factor_values, int workspaces)
      : f(factor), lower(matrix), lower_values(matrix_values), values(factor_values), spaces(workspaces),
        owner(factor.num_supernodes()), stack_offset(factor.num_supernodes()) {}
  // The update matrix of supernode s (after it was pushed).
  const double* update_of(int s) const { return spaces[owner[s]].stack.get() + stack_offset[s]; }
};

// Supernode s of the factor: k columns from `first`, r rows, m = r - k below its diagonal
// block, and its r by k column-major block of values.
struct Supernode {
  int first, k, r, m;
  const int* rows;
  double* block;
};

// Returns supernode s of f, its block in `values`.
Supernode supernode(const SymbolicFactor& f, PageArray<double>& values, int s) {
  const int k = f.first_column[s + 1] - f.first_column[s];
  const int r = f.row_start[s + 1] - f.row_start[s];
  return {f.first_column[s], k, r, r - k, f.rows.data() + f.row_start[s], values.data() + f.value_start[s]};
}

// The most update rows that the children of one supernode of f have together.
int most_child_rows(const SymbolicFactor& f) {
  int most = 0;
  for (int s = 0; s < f.num_supernodes(); ++s) {
    int rows = 0;
    for (int c = f.child_start[s]; c < f.child_start[s + 1]; ++c) {
      const int child = f.children[c];
      rows += f.row_start[child + 1] - f.row_start[child] - (f.first_column[child + 1] - f.first_column[child]);
    }
    most = std::max(most, rows);
  }
  return most;
}

// Fills the block of supernode s with A's columns and the children's contributions to its
// pivot columns; records the children (w.children, w.first_update_column) for push_update.
void assemble_block(const Multifrontal& mf, int s, const Supernode& node, Workspace& w) {
  const SymbolicFactor& f = mf.f;
  for (int i = 0; i < node.r; ++i) w.position[node.rows[i]] = i;
  std::fill(node.block, node.block + static_cast<long>(node.r) * node.k, 0.0);
  gather_columns(mf.lower, mf.lower_values, node.first, node.k, node.r, w.position, node.block);
  w.children.clear();
  w.first_update_column.clear();
  int* relative = w.relative.data();
  for (int c = f.child_start[s]; c < f.child_start[s + 1]; ++c) {
    const int child = f.children[c];
    const int child_k = f.first_column[child + 1] - f.first_column[child];
    const int child_m = f.row_start[child + 1] - f.row_start[child] - child_k;
    const int* child_rows = f.rows.data() + f.row_start[child] + child_k;
    for (int q = 0; q < child_m; ++q) relative[q] = w.position[child_rows[q]];
    w.children.push_back({mf.update_of(child), child_m, relative});
    w.first_update_column.push_back(add_to_pivot_block(w.children.back(), node.k, node.r, node.block));
    relative += child_m;
  }
}

// After the block of supernode s is factored: builds its update matrix -L21 L21^T (on `team`
// threads when large) plus the rest of its children's updates on top of workspace `me`'s stack,
// then moves it down over the children's that wait on that stack (on its top, the first such child
// lowest).
void push_update(Multifrontal& mf, int s, const Supernode& node, int me, int team) {
  const SymbolicFactor& f = mf.f;
  Workspace& w = mf.spaces[me];
  double* u = w.stack.get() + w.top;
  if (node.m > 0) negative_lower_product(node.block + node.k, node.r, node.m, node.k, u, team);
  for (size_t c = 0; c < w.children.size(); ++c)
    add_to_update(w.children[c], w.first_update_column[c], node.k, u, node.m);
  size_t base = w.top;
  for (int c = f.child_start[s]; c < f.child_start[s + 1]; ++c)
    if (mf.owner[f.children[c]] == me) {
      base = mf.stack_offset[f.children[c]];
      break;
    }
  const size_t size = node.m > 0 ? packed_size(node.m) : 0;
  if (size > 0 && base != w.top) std::memmove(w.stack.get() + base, u, size * sizeof(double));
  mf.owner[s] = me;
  mf.stack_offset[s] = base;
  w.top = base + size;
}

// Factors supernode s on workspace `me`, its dense kernels on `team` threads when large (node-level
// parallelism: the same bits for any team). Returns -1, or the column (in the factor's order) whose
// pivot is not positive.
int factor_supernode(Multifrontal& mf, int s, int me, int team = 1) {
  const Supernode node = supernode(mf.f, mf.values, s);
  assemble_block(mf, s, node, mf.spaces[me]);
  const int failed = factor_panel(node.block, node.r, node.k, team);
  if (failed >= 0) return node.first + failed;
  push_update(mf, s, node, me, team);
  return -1;
}

// The schedule's subtrees on `team` threads (workspace t for thread t, each subtree's root update
// left on its thread's stack), then its top on workspace `team`, supernode after supernode, each
// large one's dense kernels on the whole team. Returns -1, or the column of the
// first supernode (in the serial order) whose pivot is not positive.
int factorize_by_subtrees(Multifrontal& mf, const SubtreeSchedule& schedule, int team) {
  const SymbolicFactor& f = mf.f;
  const int subtrees = static_cast<int>(schedule.root.size());
  const int relative_size = most_child_rows(f);
  // A thread's stack: the root updates of the subtrees it ran, below the one it runs.
  size_t roots = 0, largest = 0;
  for (int t = 0; t < subtrees; ++t) {
    const int root = schedule.root[t];
    const int k = f.first_column[root + 1] - f.first_column[root];
    roots += packed_size(f.row_start[root + 1] - f.row_start[root] - k);
    largest = std::max(largest, schedule.stack[t]);
  }
  for (int me = 0; me < team; ++me) mf.spaces[me].size_for(f, roots + largest, relative_size);
  mf.spaces[team].size_for(f, schedule.top_stack, relative_size);
  std::vector<int> failed_supernode(subtrees, -1), failed_column(subtrees, -1);
#pragma omp parallel num_threads(team)
  {
    const int me = thread_index();
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < subtrees; ++t) {
      const size_t start = mf.spaces[me].top;
      for (int s = schedule.first[t]; s <= schedule.root[t]; ++s) {
        const int column = factor_supernode(mf, s, me);
        if (column >= 0) {
          failed_supernode[t] = s;
          failed_column[t] = column;
          mf.spaces[me].top = start;  // drops the failed subtree's updates
          break;
        }
      }
    }
  }
  // The serial order fails at the lowest failing supernode: a subtree's, or a top one below it
  // (whose descendants all lie below it, so were factored).
  int first_failure = f.num_supernodes(), column = -1;
  for (int t = 0; t < subtrees; ++t)
    if (failed_supernode[t] >= 0 && failed_supernode[t] < first_failure) {
      first_failure = failed_supernode[t];
      column = failed_column[t];
    }
  for (int s : schedule.top) {
    if (s > first_failure) break;
    const int top_column = factor_supernode(mf, s, team, team);
    if (top_column >= 0) return top_column;
  }
  return column;
}

}  // namespace

void factorize_numeric(const Analysis& analysis, const std::vector<double>& a_values, FactorValues& factor,
                       const SubtreeSchedule* schedule, int team) {
  const std::vector<int>& source = analysis.lower.source;
  // Work only: the permuted lower triangle's values, freed on return.
  std::vector<double> lower_values(source.size());
  for (size_t p = 0; p < source.size(); ++p) lower_values[p] = a_values[source[p]];
  eliminate_prefix(analysis.prefix, lower_values, analysis.perm, factor.prefix_diagonal, factor.prefix_below);
  factorize_supernodal(analysis.symbolic, analysis.lower.pattern, lower_values.data(), analysis.perm,
                       factor.supernodal, schedule, team);
}

void throw_not_positive_definite(int original_column) {
  throw NotPositiveDefinite("SparseCholesky: matrix is not positive definite (pivot of column " +
                            std::to_string(original_column) + " is not positive)");
}

void factorize_supernodal(const SymbolicFactor& f, const Pattern& lower, const double* lower_values,
                          const std::vector<int>& original_column, PageArray<double>& values,
                          const SubtreeSchedule* schedule, int team) {
  const int ns = f.num_supernodes();
  // Every block is filled before it is read (assemble_block): new storage is first touched by the
  // team.
  if (values.size() != f.value_start[ns]) assign_by_team(values, f.value_start[ns], 0.0, team);
  int failed = -1;
  if (schedule != nullptr && team > 1 && schedule->root.size() >= 2) {
    Multifrontal mf(f, lower, lower_values, values, team + 1);
    failed = factorize_by_subtrees(mf, *schedule, team);
  } else {
    Multifrontal mf(f, lower, lower_values, values, 1);
    mf.spaces[0].size_for(f, f.stack_size, most_child_rows(f));
    for (int s = 0; s < ns && failed < 0; ++s) failed = factor_supernode(mf, s, 0, team);
  }
  if (failed >= 0) throw_not_positive_definite(original_column[failed]);
}

}  // namespace meshik::sparse
