// Column counts of the Cholesky factor from the elimination tree (Gilbert, Ng and Peyton's
// row-subtree method with skeleton leaves and least common ancestors).
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// lower:  lower triangle of a symmetric matrix (column j: rows i >= j, in any order)
// first_column: the counts are those of the trailing columns first_column.. (n of them, whose rows
//         are all >= first_column), numbered from 0 in `parent` and in the result
// parent: the elimination tree of those columns (n entries), numbered in a postorder
//         (parent[j] > j or -1, every subtree a run of consecutive columns)
// Returns n counts: nnz(L(:, j)), diagonal included. Time O(nnz * alpha(n)).
std::vector<int> column_counts(const Pattern& lower, int first_column, const std::vector<int>& parent);

}  // namespace meshik::sparse
