// Column counts of the Cholesky factor from the elimination tree (Gilbert, Ng and Peyton's
// row-subtree method with skeleton leaves and least common ancestors).
#pragma once

#include <vector>

#include "sparse/symmetric_graph.h"

namespace meshik::sparse {

// graph:  adjacency of a symmetric n by n matrix (column j: the neighbours of node j)
// parent: its elimination tree (n entries), post: a postorder of it (n entries)
// Returns n counts: nnz(L(:, j)), diagonal included. Time O(nnz(A) * alpha(n)).
std::vector<int> column_counts(const Pattern& graph, const std::vector<int>& parent,
                               const std::vector<int>& post);

}  // namespace meshik::sparse
