#include "sparse/dense_kernels.h"

#include <cmath>

namespace meshik::sparse {

int factor_panel(double* panel, int rows, int cols) {
  for (int j = 0; j < cols; ++j) {
    double* cj = panel + static_cast<long>(j) * rows;
    // Left-looking: subtract the contributions of the finished columns t < j.
    for (int t = 0; t < j; ++t) {
      const double* ct = panel + static_cast<long>(t) * rows;
      const double f = ct[j];
      for (int i = j; i < rows; ++i) cj[i] -= ct[i] * f;
    }
    if (!(cj[j] > 0.0)) return j;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inverse = 1.0 / d;
    for (int i = j + 1; i < rows; ++i) cj[i] *= inverse;
  }
  return -1;
}

void negative_lower_product(const double* l21, int ld, int m, int k, double* u) {
  for (int q = 0; q < m; ++q) {
    double* uq = u + packed_column_offset(m, q) - q;  // uq[p] is entry (p, q), p >= q
    for (int p = q; p < m; ++p) uq[p] = 0.0;
    for (int t = 0; t < k; ++t) {
      const double* lt = l21 + static_cast<long>(t) * ld;
      const double f = lt[q];
      for (int p = q; p < m; ++p) uq[p] -= lt[p] * f;
    }
  }
}

}  // namespace meshik::sparse
