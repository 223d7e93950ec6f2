#include "sparse/elimination_tree.h"

namespace meshik::sparse {

std::vector<int> elimination_tree(const PermutedView& graph) {
  const int n = graph.size();
  std::vector<int> parent(n, -1);
  // ancestor[i]: a known ancestor of i (path-compressed), -1 when i is a root so far.
  std::vector<int> ancestor(n, -1);
  for (int k = 0; k < n; ++k)
    graph.for_each_neighbour(k, [&](int i) {
      // A(i, k) != 0 with i < k: k is an ancestor of i; climb to i's current root.
      while (i != -1 && i < k) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) parent[i] = k;
        i = next;
      }
    });
  return parent;
}

std::vector<int> tree_postorder(const std::vector<int>& parent) {
  const int n = static_cast<int>(parent.size());
  // size[j]: the nodes of j's subtree (children precede their parent).
  std::vector<int> size(n, 1);
  for (int j = 0; j < n; ++j)
    if (parent[j] != -1) size[parent[j]] += size[j];
  // The postorder lays the roots' subtrees out in increasing order, and within j's block its
  // children's subtrees in increasing order, then j. Going down from the largest node, each
  // takes the last free block of its parent's (a root: the forest's) range, and its own last
  // position.
  std::vector<int> post(n), free_end(n);
  int forest_end = n;
  for (int j = n - 1; j >= 0; --j) {
    int& end = parent[j] == -1 ? forest_end : free_end[parent[j]];
    post[end - 1] = j;
    free_end[j] = end - 1;
    end -= size[j];
  }
  return post;
}

std::vector<int> relabel_tree(const std::vector<int>& parent, const std::vector<int>& post) {
  const int n = static_cast<int>(parent.size());
  std::vector<int> new_index(n);
  for (int k = 0; k < n; ++k) new_index[post[k]] = k;
  std::vector<int> relabeled(n);
  for (int k = 0; k < n; ++k) relabeled[k] = parent[post[k]] == -1 ? -1 : new_index[parent[post[k]]];
  return relabeled;
}

}  // namespace meshik::sparse
