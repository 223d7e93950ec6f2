// Assembly of the kept operator G and of the eliminated normal matrix K.
#include "gradient_operator.h"

#include <algorithm>

namespace meshik {

std::vector<MatrixEntry> kept_gradient_operator(const TriangleFrames& frames, const int* triangles,
                                                int num_vertices) {
  std::vector<MatrixEntry> entries;
  entries.reserve(12 * static_cast<size_t>(frames.num_triangles));
  for (int j = 0; j < frames.num_triangles; ++j) {
    const double* inverse = frames.frame_inverse.data() + 9 * static_cast<size_t>(j);
    const int* t = triangles + 3 * j;
    // T[c][r] = sum_s (x_{s+1} - x_0)[c] V^{-1}[s][r], with x_3 the fourth vertex (column #V + j).
    const int columns[4] = {t[0], t[1], t[2], num_vertices + j};
    for (int r = 0; r < 3; ++r) {
      const double s0 = inverse[r], s1 = inverse[3 + r], s2 = inverse[6 + r];
      const int row = 3 * j + r;
      entries.push_back({row, columns[0], -(s0 + s1 + s2)});
      entries.push_back({row, columns[1], s0});
      entries.push_back({row, columns[2], s1});
      entries.push_back({row, columns[3], s2});
    }
  }
  return entries;
}

CscMatrix eliminated_normal_matrix(const TriangleFrames& frames, const int* triangles,
                                   int num_vertices) {
  const int m = frames.num_triangles;
  // Candidate rows of column v: v itself and the other corners of every triangle around v.
  std::vector<int> start(num_vertices + 1, 0);
  for (int v = 0; v < num_vertices; ++v) start[v + 1] = 1;
  for (int e = 0; e < 3 * m; ++e) start[triangles[e] + 1] += 2;
  for (int v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  std::vector<int> rows(start[num_vertices]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int v = 0; v < num_vertices; ++v) rows[fill[v]++] = v;
  for (int j = 0; j < m; ++j) {
    const int* t = triangles + 3 * j;
    for (int q = 0; q < 3; ++q) {
      rows[fill[t[q]]++] = t[(q + 1) % 3];
      rows[fill[t[q]]++] = t[(q + 2) % 3];
    }
  }
  // Sort and deduplicate each column, compacting in place.
  CscMatrix k;
  k.rows = k.cols = num_vertices;
  k.col_start.assign(num_vertices + 1, 0);
  int out = 0;
  for (int v = 0; v < num_vertices; ++v) {
    std::sort(rows.begin() + start[v], rows.begin() + start[v + 1]);
    const int first = out;
    for (int s = start[v]; s < start[v + 1]; ++s)
      if (out == first || rows[out - 1] != rows[s]) rows[out++] = rows[s];
    k.col_start[v + 1] = out;
  }
  rows.resize(out);
  k.row_index = std::move(rows);
  k.values.assign(out, 0.0);

  // Per triangle and coordinate the energy is |sum_q x_q g_q - target|^2: add the Gram of g.
  for (int j = 0; j < m; ++j) {
    const int* t = triangles + 3 * j;
    const double* g = frames.gradient.data() + 6 * static_cast<size_t>(j);
    for (int p = 0; p < 3; ++p) {
      const int col = t[p];
      const auto begin = k.row_index.begin() + k.col_start[col];
      const auto end = k.row_index.begin() + k.col_start[col + 1];
      for (int q = 0; q < 3; ++q) {
        const auto at = std::lower_bound(begin, end, t[q]);
        k.values[at - k.row_index.begin()] += g[2 * p] * g[2 * q] + g[2 * p + 1] * g[2 * q + 1];
      }
    }
  }
  return k;
}

CscMatrix restricted_lower(const CscMatrix& k, const std::vector<int>& row_of_vertex, int num_rows) {
  // Increasing vertex order keeps row >= col for the lower triangle.
  CscMatrix lower;
  lower.rows = lower.cols = num_rows;
  lower.col_start.reserve(num_rows + 1);
  lower.row_index.reserve(k.row_index.size() / 2 + row_of_vertex.size());
  lower.values.reserve(k.row_index.size() / 2 + row_of_vertex.size());
  lower.col_start.push_back(0);
  for (size_t v = 0; v < row_of_vertex.size(); ++v) {
    const int col = row_of_vertex[v];
    if (col < 0) continue;
    for (int s = k.col_start[v]; s < k.col_start[v + 1]; ++s) {
      const int row = row_of_vertex[k.row_index[s]];
      if (row >= col) {
        lower.row_index.push_back(row);
        lower.values.push_back(k.values[s]);
      }
    }
    lower.col_start.push_back(static_cast<int>(lower.row_index.size()));
  }
  return lower;
}

}  // namespace meshik
