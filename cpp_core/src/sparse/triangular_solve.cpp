#include "sparse/triangular_solve.h"

namespace meshik::sparse {

void forward_solve(const SymbolicFactor& f, const std::vector<double>& values, double* x, int nrhs) {
  const long w = nrhs;
  for (int s = 0; s < f.num_supernodes(); ++s) {
    const int k = f.first_column[s + 1] - f.first_column[s];
    const int r = f.row_start[s + 1] - f.row_start[s];
    const int* rows = f.rows.data() + f.row_start[s];
    const double* block = values.data() + f.value_start[s];
    double* xs = x + f.first_column[s] * w;  // the supernode's k rows are consecutive
    for (int j = 0; j < k; ++j) {
      const double* lj = block + static_cast<long>(j) * r;
      double* xj = xs + j * w;
      const double inverse = 1.0 / lj[j];
      for (long c = 0; c < w; ++c) xj[c] *= inverse;
      for (int i = j + 1; i < k; ++i) {
        double* xi = xs + i * w;
        for (long c = 0; c < w; ++c) xi[c] -= lj[i] * xj[c];
      }
    }
    for (int i = k; i < r; ++i) {
      double* xi = x + rows[i] * w;
      for (int j = 0; j < k; ++j) {
        const double lij = block[static_cast<long>(j) * r + i];
        const double* xj = xs + j * w;
        for (long c = 0; c < w; ++c) xi[c] -= lij * xj[c];
      }
    }
  }
}

void backward_solve(const SymbolicFactor& f, const std::vector<double>& values, double* x, int nrhs) {
  const long w = nrhs;
  for (int s = f.num_supernodes() - 1; s >= 0; --s) {
    const int k = f.first_column[s + 1] - f.first_column[s];
    const int r = f.row_start[s + 1] - f.row_start[s];
    const int* rows = f.rows.data() + f.row_start[s];
    const double* block = values.data() + f.value_start[s];
    double* xs = x + f.first_column[s] * w;
    for (int i = k; i < r; ++i) {
      const double* xi = x + rows[i] * w;
      for (int j = 0; j < k; ++j) {
        const double lij = block[static_cast<long>(j) * r + i];
        double* xj = xs + j * w;
        for (long c = 0; c < w; ++c) xj[c] -= lij * xi[c];
      }
    }
    for (int j = k - 1; j >= 0; --j) {
      const double* lj = block + static_cast<long>(j) * r;
      double* xj = xs + j * w;
      for (int i = j + 1; i < k; ++i) {
        const double* xi = xs + i * w;
        for (long c = 0; c < w; ++c) xj[c] -= lj[i] * xi[c];
      }
      const double inverse = 1.0 / lj[j];
      for (long c = 0; c < w; ++c) xj[c] *= inverse;
    }
  }
}

}  // namespace meshik::sparse
