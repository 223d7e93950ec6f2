#include "sparse/dense_kernels.h"

#include <algorithm>
#include <cmath>

#include "sparse/simd.h"

namespace meshik::sparse {

namespace {

// kLanes doubles from p when Full, else the first `count` (the rest zero).
template <bool Full>
Vec load_rows(const double* p, int count) {
  if constexpr (Full) return load(p);
  else return load_first(p, count);
}

// cj[p0 .. p0+count) -= sum_{t<j} ct[p0 .. p0+count) * ct[j] for the columns ct of the panel;
// count == kLanes when Full.
template <bool Full>
void update_column_rows(double* panel, int rows, int j, int p0, int count) {
  double* cj = panel + static_cast<long>(j) * rows;
  Vec acc = load_rows<Full>(cj + p0, count);
  for (int t = 0; t < j; ++t) {
    const double* ct = panel + static_cast<long>(t) * rows;
    acc -= load_rows<Full>(ct + p0, count) * broadcast(ct[j]);
  }
  if constexpr (Full) store(cj + p0, acc);
  else store_lanes(cj + p0, acc, 0, count);
}

// Rows p0 .. p0+count of the NC columns q0 .. q0+NC-1 of U = -L21 L21^T (count == kLanes when
// Full), stored into the packed lower triangle u (m by m) where they lie on or below the
// diagonal.
template <int NC, bool Full>
void product_tile(const double* l21, int ld, int m, int k, int q0, int p0, int count, double* u) {
  Vec acc[NC] = {};
  for (int t = 0; t < k; ++t) {
    const double* lt = l21 + static_cast<long>(t) * ld;
    const Vec a = load_rows<Full>(lt + p0, count);
    for (int c = 0; c < NC; ++c) acc[c] += a * broadcast(lt[q0 + c]);
  }
  for (int c = 0; c < NC; ++c) {
    const int q = q0 + c;
    double* column = u + packed_column_offset(m, q) - q;  // column[p] is U(p, q), p >= q
    const int first_lane = std::max(q - p0, 0);
    if (Full && first_lane == 0) store(column + p0, -acc[c]);
    else if (first_lane < count) store_lanes(column + p0, -acc[c], first_lane, count);
  }
}

// Columns q0 .. q0+NC-1 of U = -L21 L21^T, tile by tile from the diagonal down.
template <int NC>
void product_columns(const double* l21, int ld, int m, int k, int q0, double* u) {
  int p0 = q0;
  for (; p0 + kLanes <= m; p0 += kLanes) product_tile<NC, true>(l21, ld, m, k, q0, p0, kLanes, u);
  if (p0 < m) product_tile<NC, false>(l21, ld, m, k, q0, p0, m - p0, u);
}

}  // namespace

int factor_panel(double* panel, int rows, int cols) {
  for (int j = 0; j < cols; ++j) {
    // Left-looking: subtract the contributions of the finished columns t < j.
    int p0 = j;
    for (; p0 + kLanes <= rows; p0 += kLanes) update_column_rows<true>(panel, rows, j, p0, kLanes);
    if (p0 < rows) update_column_rows<false>(panel, rows, j, p0, rows - p0);
    double* cj = panel + static_cast<long>(j) * rows;
    if (!(cj[j] > 0.0)) return j;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inverse = 1.0 / d;
    for (int i = j + 1; i < rows; ++i) cj[i] *= inverse;
  }
  return -1;
}

void negative_lower_product(const double* l21, int ld, int m, int k, double* u) {
  constexpr int kColumns = 4;  // columns per tile
  int q0 = 0;
  for (; q0 + kColumns <= m; q0 += kColumns) product_columns<kColumns>(l21, ld, m, k, q0, u);
  switch (m - q0) {
    case 3: product_columns<3>(l21, ld, m, k, q0, u); break;
    case 2: product_columns<2>(l21, ld, m, k, q0, u); break;
    case 1: product_columns<1>(l21, ld, m, k, q0, u); break;
    default: break;
  }
}

}  // namespace meshik::sparse
