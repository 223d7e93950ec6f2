#include "sparse/permuted_matrix.h"

#include <algorithm>

namespace meshik::sparse {

Pattern lower_pattern(const CscMatrix& a) {
  Pattern lower;
  lower.n = a.cols;
  lower.col_start.assign(a.cols + 1, 0);
  lower.row_index.reserve(a.row_index.size());
  for (int j = 0; j < a.cols; ++j) {
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p)
      if (a.row_index[p] >= j) lower.row_index.push_back(a.row_index[p]);
    lower.col_start[j + 1] = static_cast<int>(lower.row_index.size());
  }
  return lower;
}

PermutedMatrix permute_symmetric(const CscMatrix& a, const std::vector<int>& inverse_perm,
                                 Triangle triangle) {
  const int n = a.cols;
  const bool upper = triangle == Triangle::kUpper;
  // Entry (i, j) of A's lower part lands in column max(pi, pj) of C's upper triangle, or in
  // column min(pi, pj) of its lower triangle.
  auto target_column = [&](int pi, int pj) { return upper ? std::max(pi, pj) : std::min(pi, pj); };
  std::vector<int> next(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i >= j) ++next[target_column(inverse_perm[i], inverse_perm[j]) + 1];
    }
  for (int j = 0; j < n; ++j) next[j + 1] += next[j];
  PermutedMatrix c;
  c.pattern.n = n;
  c.pattern.col_start = next;
  c.pattern.row_index.resize(next[n]);
  c.source.resize(next[n]);
  for (int j = 0; j < n; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i < j) continue;
      const int pi = inverse_perm[i], pj = inverse_perm[j];
      const int q = next[target_column(pi, pj)]++;
      c.pattern.row_index[q] = upper ? std::min(pi, pj) : std::max(pi, pj);
      c.source[q] = p;
    }
  return c;
}

Pattern transpose(const Pattern& p) {
  Pattern t;
  t.n = p.n;
  t.col_start.assign(p.n + 1, 0);
  for (int i : p.row_index) ++t.col_start[i + 1];
  for (int j = 0; j < p.n; ++j) t.col_start[j + 1] += t.col_start[j];
  t.row_index.resize(p.row_index.size());
  std::vector<int> next(t.col_start.begin(), t.col_start.end() - 1);
  for (int j = 0; j < p.n; ++j)
    for (int q = p.col_start[j]; q < p.col_start[j + 1]; ++q) t.row_index[next[p.row_index[q]]++] = j;
  return t;
}

}  // namespace meshik::sparse
