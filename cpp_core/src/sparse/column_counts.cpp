#include "sparse/column_counts.h"

namespace meshik::sparse {

namespace {

// Root of i's set in the union-find forest `ancestor` (ancestor[r] == r for a root), with
// path compression.
int find_root(std::vector<int>& ancestor, int i) {
  int root = i;
  while (ancestor[root] != root) root = ancestor[root];
  while (ancestor[i] != root) {
    const int next = ancestor[i];
    ancestor[i] = root;
    i = next;
  }
  return root;
}

}  // namespace

std::vector<int> column_counts(const Pattern& lower, int first_column, const std::vector<int>& parent) {
  const int n = static_cast<int>(parent.size());
  // first[j]: the first (smallest) descendant of j, j included: j's subtree is first[j] .. j.
  std::vector<int> first(n);
  for (int j = 0; j < n; ++j) first[j] = j;
  for (int j = 0; j < n; ++j)
    if (parent[j] != -1 && first[j] < first[parent[j]]) first[parent[j]] = first[j];
  // delta[j]: count contributions that sum over the subtree of j to nnz(L(:, j)); 1 for a leaf.
  std::vector<int> delta(n);
  // Per row i: the largest `first` of a leaf of row subtree i seen so far, and that leaf.
  std::vector<int> max_first(n, -1), previous_leaf(n, -1);
  std::vector<int> ancestor(n);
  for (int j = 0; j < n; ++j) {
    delta[j] = first[j] == j ? 1 : 0;
    ancestor[j] = j;
  }
  const int* rows = lower.row_index.data();
  const int* column_start = lower.col_start.data() + first_column;
  for (int j = 0; j < n; ++j) {
    if (parent[j] != -1) --delta[parent[j]];
    // Row j's subtree is complete (its leaves are earlier columns): its max_first now makes the
    // diagonal entry fail the leaf test below.
    max_first[j] = j;
    const int first_j = first[j];
    for (int p = column_start[j]; p < column_start[j + 1]; ++p) {
      const int i = rows[p] - first_column;
      // j is a leaf of row subtree i iff A(i, j) != 0, i > j, and no earlier leaf of that
      // subtree lies inside j's subtree (first[j] > max_first[i]).
      if (first_j <= max_first[i]) continue;
      max_first[i] = first_j;
      const int prev = previous_leaf[i];
      previous_leaf[i] = j;
      ++delta[j];
      // For every leaf but the first, the least common ancestor with the previous leaf was
      // counted twice.
      if (prev != -1) --delta[find_root(ancestor, prev)];
    }
    if (parent[j] != -1) ancestor[j] = parent[j];
  }
  // Sum over subtrees: children have smaller indices than their parents.
  for (int j = 0; j < n; ++j)
    if (parent[j] != -1) delta[parent[j]] += delta[j];
  return delta;
}

}  // namespace meshik::sparse
