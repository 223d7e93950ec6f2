// A sparse matrix pattern in compressed sparse column form, used inside the factorization.
#pragma once

#include <vector>

namespace meshik::sparse {

// n by n pattern: column j holds row_index[col_start[j] .. col_start[j + 1]).
struct Pattern {
  int n = 0;
  std::vector<int> col_start;  // n + 1 offsets
  std::vector<int> row_index;  // nnz row indices
};

}  // namespace meshik::sparse
