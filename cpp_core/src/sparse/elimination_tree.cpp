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
  // Children lists: first_child / next_sibling, built backwards so they come out increasing.
  std::vector<int> first_child(n, -1), next_sibling(n, -1);
  for (int j = n - 1; j >= 0; --j) {
    if (parent[j] == -1) continue;
    next_sibling[j] = first_child[parent[j]];
    first_child[parent[j]] = j;
  }
  std::vector<int> post;
  post.reserve(n);
  std::vector<int> stack;
  for (int root = 0; root < n; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int top = stack.back();
      const int child = first_child[top];
      if (child == -1) {
        // All children done: emit top and continue with its next sibling.
        post.push_back(top);
        stack.pop_back();
      } else {
        first_child[top] = next_sibling[child];
        stack.push_back(child);
      }
    }
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
