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

void keep_induced_subgraph(Pattern& graph, const std::vector<int>& local) {
  // Kept node v becomes t <= v and its list only shrinks, so writing entry q and offset t + 1
  // never overtakes what is still to be read (v's old offsets are read before t + 1 <= v + 1 is
  // written).
  int kept = 0, q = 0, old_begin = 0;
  for (int v = 0; v < graph.n; ++v) {
    const int old_end = graph.col_start[v + 1];
    if (local[v] >= 0) {
      for (int p = old_begin; p < old_end; ++p) {
        const int u = local[graph.row_index[p]];
        if (u >= 0) graph.row_index[q++] = u;
      }
      graph.col_start[++kept] = q;
    }
    old_begin = old_end;
  }
  graph.n = kept;
  graph.col_start.resize(kept + 1);
  graph.row_index.resize(q);
}

}  // namespace meshik::sparse
