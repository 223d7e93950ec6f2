#include "sparse/symmetric_graph.h"

namespace meshik::sparse {

Pattern adjacency_graph(const CscMatrix& a) {
  const int n = a.cols;
  Pattern g;
  g.n = n;
  g.col_start.assign(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i > j) {
        ++g.col_start[i + 1];
        ++g.col_start[j + 1];
      }
    }
  for (int j = 0; j < n; ++j) g.col_start[j + 1] += g.col_start[j];
  g.row_index.resize(g.col_start[n]);
  std::vector<int> next(g.col_start.begin(), g.col_start.end() - 1);
  // Column by column: list i receives the columns j < i in increasing order before its own
  // column's rows (all > i) arrive in increasing order, so every list comes out sorted.
  for (int j = 0; j < n; ++j)
    for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
      const int i = a.row_index[p];
      if (i > j) {
        g.row_index[next[j]++] = i;
        g.row_index[next[i]++] = j;
      }
    }
  return g;
}

}  // namespace meshik::sparse
