// Assembly of the kept operator G and of the eliminated normal matrix K.
#include "gradient_operator.h"

#include <algorithm>

namespace meshik {

std::vector<MatrixEntry> kept_gradient_operator(const TriangleFrames& frames, const int* triangles,
                                                int num_vertices) {
  std::vector<MatrixEntry> entries;
  entries.reserve(12 * static_cast<size_t>(frames.num_triangles));
  for (int j = 0; j < frames.num_triangles; ++j) {
    double inverse[9];
    rest_frame_inverse(frames.gradient.data(), frames.plane_basis.data(), j, inverse);
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

CscMatrix eliminated_lower_pattern(const int* triangles, int num_triangles, const std::vector<int>& row_of_vertex,
                                   int num_rows) {
  // Candidate rows of column c: c itself and the larger rows of the other corners of every
  // triangle around it (each edge twice inside the mesh).
  std::vector<int> start(num_rows + 1, 0);
  for (int c = 0; c < num_rows; ++c) start[c + 1] = 1;
  for (int j = 0; j < num_triangles; ++j)
    for (int q = 0; q < 3; ++q) {
      const int a = row_of_vertex[triangles[3 * j + q]], b = row_of_vertex[triangles[3 * j + (q + 1) % 3]];
      ++start[std::min(a, b) + 1];
    }
  for (int c = 0; c < num_rows; ++c) start[c + 1] += start[c];
  std::vector<int> rows(start[num_rows]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int c = 0; c < num_rows; ++c) rows[fill[c]++] = c;
  for (int j = 0; j < num_triangles; ++j)
    for (int q = 0; q < 3; ++q) {
      const int a = row_of_vertex[triangles[3 * j + q]], b = row_of_vertex[triangles[3 * j + (q + 1) % 3]];
      rows[fill[std::min(a, b)]++] = std::max(a, b);
    }
  // Sort and deduplicate each column, compacting in place.
  CscMatrix pattern;
  pattern.rows = pattern.cols = num_rows;
  pattern.col_start.assign(num_rows + 1, 0);
  int out = 0;
  for (int c = 0; c < num_rows; ++c) {
    std::sort(rows.begin() + start[c], rows.begin() + start[c + 1]);
    const int first = out;
    for (int s = start[c]; s < start[c + 1]; ++s)
      if (out == first || rows[out - 1] != rows[s]) rows[out++] = rows[s];
    pattern.col_start[c + 1] = out;
  }
  rows.resize(out);
  pattern.row_index = std::move(rows);
  return pattern;
}

namespace {

// Adds to `values` (eliminated_lower_values' layout) the Gram terms of every triangle corner whose
// column lies in [first_column, last_column), triangles in increasing order; the other columns'
// entries are left alone. Arguments as eliminated_lower_values'.
void add_corner_grams(const TriangleFrames& frames, const int* triangles, const std::vector<int>& row_of_vertex,
                      const CscMatrix& pattern, int first_column, int last_column, double* __restrict values) {
  const auto in_range = [first_column, last_column](int column) {
    return column >= first_column && column < last_column;
  };
  for (int j = 0; j < frames.num_triangles; ++j) {
    const int* t = triangles + 3 * j;
    if (!in_range(row_of_vertex[t[0]]) && !in_range(row_of_vertex[t[1]]) && !in_range(row_of_vertex[t[2]])) continue;
    double g[6];
    corner_gradients(frames.gradient.data() + kGradientEntries * static_cast<size_t>(j), g);
    for (int p = 0; p < 3; ++p) {
      const int col = row_of_vertex[t[p]];
      if (!in_range(col)) continue;
      const auto begin = pattern.row_index.begin() + pattern.col_start[col];
      const auto end = pattern.row_index.begin() + pattern.col_start[col + 1];
      for (int q = 0; q < 3; ++q) {
        const int row = row_of_vertex[t[q]];
        if (row < col) continue;
        const auto at = std::lower_bound(begin, end, row);
        values[at - pattern.row_index.begin()] += g[2 * p] * g[2 * q] + g[2 * p + 1] * g[2 * q + 1];
      }
    }
  }
}

}  // namespace

std::vector<double> eliminated_lower_values(const TriangleFrames& frames, const int* triangles,
                                            const std::vector<int>& row_of_vertex, const CscMatrix& pattern,
                                            int team) {
  std::vector<double> values(pattern.row_index.size(), 0.0);
  // Per triangle and coordinate the energy is |sum_q x_q g_q - target|^2: add the Gram of g. Each
  // thread takes a range of columns holding about an equal share of the entries, and goes over all
  // the triangles for the corners in its range.
  const int parts = std::max(1, std::min(team, pattern.cols));
  std::vector<int> first_column(parts + 1, pattern.cols);
  for (int part = 0; part < parts; ++part) {
    const size_t share = pattern.row_index.size() * static_cast<size_t>(part) / parts;
    first_column[part] = static_cast<int>(
        std::upper_bound(pattern.col_start.begin(), pattern.col_start.end() - 1, static_cast<int>(share)) -
        pattern.col_start.begin() - 1);
  }
#pragma omp parallel for schedule(static, 1) num_threads(parts) if (parts > 1)
  for (int part = 0; part < parts; ++part)
    add_corner_grams(frames, triangles, row_of_vertex, pattern, first_column[part], first_column[part + 1],
                     values.data());
  return values;
}

}  // namespace meshik
