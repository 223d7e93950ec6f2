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

Pattern permuted_graph(const Pattern& graph, const std::vector<int>& perm, const std::vector<int>& inverse) {
  Pattern g;
  g.n = graph.n;
  g.col_start.resize(graph.n + 1);
  g.row_index.resize(graph.row_index.size());
  int q = 0;
  for (int k = 0; k < graph.n; ++k) {
    g.col_start[k] = q;
    const int v = perm[k];
    for (int p = graph.col_start[v]; p < graph.col_start[v + 1]; ++p) g.row_index[q++] = inverse[graph.row_index[p]];
  }
  g.col_start[graph.n] = q;
  return g;
}

Pattern induced_subgraph(const Pattern& graph, const std::vector<int>& kept, const std::vector<int>& local) {
  Pattern sub;
  sub.n = static_cast<int>(kept.size());
  sub.col_start.reserve(sub.n + 1);
  sub.col_start.push_back(0);
  sub.row_index.reserve(graph.row_index.size());
  for (int v : kept) {
    for (int p = graph.col_start[v]; p < graph.col_start[v + 1]; ++p)
      if (local[graph.row_index[p]] >= 0) sub.row_index.push_back(local[graph.row_index[p]]);
    sub.col_start.push_back(static_cast<int>(sub.row_index.size()));
  }
  return sub;
}

}  // namespace meshik::sparse
