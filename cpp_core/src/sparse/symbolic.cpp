#include "sparse/symbolic.h"

#include <algorithm>
#include <stdexcept>

namespace meshik::sparse {

namespace {

// Returns the supernode owning each column (n entries).
std::vector<int> supernode_of_columns(const SymbolicFactor& f) {
  std::vector<int> owner(f.n);
  for (int s = 0; s + 1 < static_cast<int>(f.first_column.size()); ++s)
    std::fill(owner.begin() + f.first_column[s], owner.begin() + f.first_column[s + 1], s);
  return owner;
}

// Supernodal tree: the parent of s holds the elimination-tree parent of s's last column (the
// columns of a supernode form a path in the tree, so that is its first row below).
// supernode_of: the owner of each column.
void supernodal_tree(const std::vector<int>& parent, const std::vector<int>& supernode_of, SymbolicFactor& f) {
  const int ns = static_cast<int>(f.first_column.size()) - 1;
  f.parent.assign(ns, -1);
  f.child_start.assign(ns + 1, 0);
  for (int s = 0; s < ns; ++s) {
    const int above = parent[f.first_column[s + 1] - 1];
    if (above == -1) continue;
    f.parent[s] = supernode_of[above];
    ++f.child_start[f.parent[s] + 1];
  }
  for (int s = 0; s < ns; ++s) f.child_start[s + 1] += f.child_start[s];
  f.children.resize(f.child_start[ns]);
  std::vector<int> next(f.child_start.begin(), f.child_start.end() - 1);
  for (int s = 0; s < ns; ++s)
    if (f.parent[s] != -1) f.children[next[f.parent[s]]++] = s;
}

// Row indices of every supernode: its own columns, then the rows below. Row i lies below
// supernode s iff L(i, j) != 0 for a column j of s, i.e. s is on the path of the supernodal
// tree from the supernode of some j < i with A(i, j) != 0 up to (not including) i's own
// supernode. Rows are taken in increasing order, so every list comes out sorted.
void row_structures(const PermutedView& graph, const SupernodePartition& partition,
                    const std::vector<int>& supernode_of, SymbolicFactor& f) {
  const int ns = static_cast<int>(partition.row_count.size());
  f.row_start.assign(ns + 1, 0);
  for (int s = 0; s < ns; ++s) f.row_start[s + 1] = f.row_start[s] + partition.row_count[s];
  f.rows.resize(f.row_start[ns]);
  std::vector<int> next(ns);  // next free slot of each supernode's list
  for (int s = 0; s < ns; ++s) {
    int p = f.row_start[s];
    for (int j = f.first_column[s]; j < f.first_column[s + 1]; ++j) f.rows[p++] = j;
    next[s] = p;
  }
  // The supernode of each node of the graph: one lookup per entry below, not two (ns, past every
  // supernode, for nodes outside the view).
  std::vector<int> node_supernode(graph.graph.n, ns);
  for (int k = 0; k < f.n; ++k) node_supernode[graph.perm[k]] = supernode_of[k];
  std::vector<int> mark(ns, -1);
  const int* parent = f.parent.data();
  int* rows = f.rows.data();
  for (int i = 0; i < f.n; ++i) {
    const int own = supernode_of[i];
    // A neighbour j > i lies in own or a later supernode, j < i in own or an earlier one.
    graph.for_each_neighbour(i, node_supernode, [&](int first) {
      for (int s = first; s < own && mark[s] != i; s = parent[s]) {
        mark[s] = i;
        rows[next[s]++] = i;
      }
    });
  }
  for (int s = 0; s < ns; ++s)
    if (next[s] != f.row_start[s + 1]) throw std::logic_error("SparseCholesky: inconsistent supernode row count");
}

}  // namespace

SymbolicFactor symbolic_factor(const PermutedView& graph, const std::vector<int>& parent,
                               const std::vector<int>& counts, const SupernodePartition& partition,
                               int column_offset) {
  SymbolicFactor f;
  f.n = graph.size();
  f.first_column = partition.first_column;
  const std::vector<int> supernode_of = supernode_of_columns(f);
  supernodal_tree(parent, supernode_of, f);
  row_structures(graph, partition, supernode_of, f);
  // Global numbering after the prefix.
  f.n += column_offset;
  for (int& c : f.first_column) c += column_offset;
  for (int& i : f.rows) i += column_offset;
  const int ns = f.num_supernodes();
  f.value_start.assign(ns + 1, 0);
  for (int s = 0; s < ns; ++s)
    f.value_start[s + 1] = f.value_start[s] + static_cast<size_t>(f.row_start[s + 1] - f.row_start[s]) *
                                                  (f.first_column[s + 1] - f.first_column[s]);
  f.stack_size = peak_stacks(f, std::vector<int>(ns, 0), 1)[0];
  for (int c : counts) f.structural_nonzeros += c;
  return f;
}

std::vector<size_t> peak_stacks(const SymbolicFactor& f, const std::vector<int>& group, int groups) {
  const int ns = f.num_supernodes();
  std::vector<size_t> pending(ns, 0);  // total size of the children's updates waiting for s
  std::vector<size_t> stack(groups, 0), peak(groups, 0);
  for (int s = 0; s < ns; ++s) {
    const int g = group[s];
    const int k = f.first_column[s + 1] - f.first_column[s];
    const size_t own = packed_size(f.row_start[s + 1] - f.row_start[s] - k);
    peak[g] = std::max(peak[g], stack[g] + own);
    stack[g] -= pending[s];
    if (f.parent[s] != -1 && group[f.parent[s]] == g) {
      stack[g] += own;
      pending[f.parent[s]] += own;
    }
  }
  return peak;
}

}  // namespace meshik::sparse
