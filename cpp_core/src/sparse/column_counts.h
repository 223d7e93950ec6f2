// Column counts of the Cholesky factor from the elimination tree (Gilbert, Ng and Peyton's
// row-subtree method with skeleton leaves and least common ancestors).
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// lower:  the lower triangle of a symmetric n by n pattern (column j holds rows i >= j)
// parent: its elimination tree (n entries), post: a postorder of it (n entries)
// Returns n counts: nnz(L(:, j)), diagonal included. Time O(nnz(lower) * alpha(n)).
std::vector<int> column_counts(const Pattern& lower, const std::vector<int>& parent,
                               const std::vector<int>& post);

}  // namespace meshik::sparse
