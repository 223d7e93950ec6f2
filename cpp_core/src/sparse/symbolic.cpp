#include "sparse/symbolic.h"

#include <algorithm>

namespace meshik::sparse {

namespace {

// Appends the rows of supernode s (columns [first, end)) to f.rows: its own columns, then the
// rows below `end` of A's columns and of its children's structures, sorted. mark: n entries,
// set to s for rows already taken. first_child / next_child: the children lists of the
// supernodal tree (-1 terminated).
void collect_rows(const Pattern& lower, int s, int first, int end, const std::vector<int>& first_child,
                  const std::vector<int>& next_child, SymbolicFactor& f, std::vector<int>& mark) {
  for (int j = first; j < end; ++j) f.rows.push_back(j);
  const size_t below = f.rows.size();
  auto take = [&](int i) {
    if (i >= end && mark[i] != s) {
      mark[i] = s;
      f.rows.push_back(i);
    }
  };
  for (int j = first; j < end; ++j)
    for (int p = lower.col_start[j]; p < lower.col_start[j + 1]; ++p) take(lower.row_index[p]);
  for (int c = first_child[s]; c != -1; c = next_child[c]) {
    const int k = f.first_column[c + 1] - f.first_column[c];
    for (int p = f.row_start[c] + k; p < f.row_start[c + 1]; ++p) take(f.rows[p]);
  }
  std::sort(f.rows.begin() + below, f.rows.end());
}

// Peak size of the update stack when supernodes are processed in order: a supernode's update
// matrix is built on top of its children's, which are then removed. Returns doubles.
size_t peak_stack(const SymbolicFactor& f) {
  const int ns = f.num_supernodes();
  std::vector<size_t> pending(ns, 0);  // total size of the children's updates waiting for s
  size_t stack = 0, peak = 0;
  for (int s = 0; s < ns; ++s) {
    const int k = f.first_column[s + 1] - f.first_column[s];
    const size_t own = packed_size(f.row_start[s + 1] - f.row_start[s] - k);
    peak = std::max(peak, stack + own);
    stack -= pending[s];
    if (f.parent[s] != -1) {
      stack += own;
      pending[f.parent[s]] += own;
    }
  }
  return peak;
}

}  // namespace

SymbolicFactor symbolic_factor(const Pattern& lower, const SupernodePartition& partition,
                               const std::vector<int>& counts) {
  SymbolicFactor f;
  f.n = lower.n;
  f.first_column = partition.first_column;
  const int ns = static_cast<int>(partition.row_count.size());
  f.supernode_of.resize(f.n);
  for (int s = 0; s < ns; ++s)
    std::fill(f.supernode_of.begin() + f.first_column[s], f.supernode_of.begin() + f.first_column[s + 1], s);
  size_t total_rows = 0;
  for (int r : partition.row_count) total_rows += r;
  f.rows.reserve(total_rows);
  f.row_start.assign(1, 0);
  f.value_start.assign(1, 0);
  f.parent.assign(ns, -1);
  std::vector<int> first_child(ns, -1), next_child(ns, -1);
  std::vector<int> mark(f.n, -1);
  for (int s = 0; s < ns; ++s) {
    const int first = f.first_column[s], end = f.first_column[s + 1];
    collect_rows(lower, s, first, end, first_child, next_child, f, mark);
    f.row_start.push_back(static_cast<int>(f.rows.size()));
    const int r = f.row_start[s + 1] - f.row_start[s];
    f.value_start.push_back(f.value_start[s] + static_cast<size_t>(r) * (end - first));
    if (r > end - first) {
      f.parent[s] = f.supernode_of[f.rows[f.row_start[s] + (end - first)]];
      next_child[s] = first_child[f.parent[s]];
      first_child[f.parent[s]] = s;
    }
  }
  f.child_start.assign(ns + 1, 0);
  for (int s = 0; s < ns; ++s)
    if (f.parent[s] != -1) ++f.child_start[f.parent[s] + 1];
  for (int s = 0; s < ns; ++s) f.child_start[s + 1] += f.child_start[s];
  f.children.resize(f.child_start[ns]);
  std::vector<int> next(f.child_start.begin(), f.child_start.end() - 1);
  for (int s = 0; s < ns; ++s)
    if (f.parent[s] != -1) f.children[next[f.parent[s]]++] = s;
  f.stack_size = peak_stack(f);
  for (int c : counts) f.structural_nonzeros += c;
  return f;
}

}  // namespace meshik::sparse
