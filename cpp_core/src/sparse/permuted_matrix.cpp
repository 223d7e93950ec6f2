#include "sparse/permuted_matrix.h"

#include <algorithm>

namespace meshik::sparse {

PermutedLower permute_lower(const CscMatrix& a, const std::vector<int>& inverse_perm) {
  const int n = a.cols;
  // Entry (i, j) of A's lower part lands in column min(pi, pj) of C's lower triangle.
  std::vector<int> next(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i >= j) ++next[std::min(inverse_perm[i], inverse_perm[j]) + 1];
    }
  for (int j = 0; j < n; ++j) next[j + 1] += next[j];
  PermutedLower c;
  c.pattern.n = n;
  c.pattern.col_start = next;
  c.pattern.row_index.resize(next[n]);
  c.source.resize(next[n]);
  for (int j = 0; j < n; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i < j) continue;
      const int pi = inverse_perm[i], pj = inverse_perm[j];
      const int q = next[std::min(pi, pj)]++;
      c.pattern.row_index[q] = std::max(pi, pj);
      c.source[q] = p;
    }
  return c;
}

}  // namespace meshik::sparse
