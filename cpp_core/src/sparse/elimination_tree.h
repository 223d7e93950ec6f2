// Elimination tree and its postorder.
#pragma once

#include <vector>

#include "sparse/symmetric_graph.h"

namespace meshik::sparse {

// graph: adjacency of a symmetric n by n matrix P A P^T (node k: the neighbours of column k).
// Returns parent, n entries: parent[j] is the parent of column j in the elimination tree of
// the Cholesky factor, or -1 for a root. parent[j] > j always.
std::vector<int> elimination_tree(const PermutedView& graph);

// parent: a forest with parent[j] > j or -1. Returns post, n entries: post[k] is the k-th
// node of a depth-first postorder (children in increasing order, every node after its
// descendants, the descendants of a node contiguous).
std::vector<int> tree_postorder(const std::vector<int>& parent);

// parent: a forest, post: a postorder of it. Returns the same forest with node post[k]
// renamed k (n entries, -1 for roots).
std::vector<int> relabel_tree(const std::vector<int>& parent, const std::vector<int>& post);

}  // namespace meshik::sparse
