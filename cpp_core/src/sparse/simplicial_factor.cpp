#include "sparse/simplicial_factor.h"

#include <cmath>
#include <string>

#include "meshik/sparse_cholesky.h"

namespace meshik::sparse {

SimplicialFactor allocate_simplicial(const std::vector<int>& counts) {
  SimplicialFactor l;
  l.n = static_cast<int>(counts.size());
  l.col_start.assign(l.n + 1, 0);
  for (int j = 0; j < l.n; ++j) l.col_start[j + 1] = l.col_start[j] + counts[j];
  l.row_index.resize(l.col_start[l.n]);
  l.values.resize(l.col_start[l.n]);
  return l;
}

namespace {

// Pattern of row k of L (columns j < k with L(k, j) != 0): the union of the elimination-tree
// paths from each i with A(i, k) != 0 up to k. Writes it to stack[top .. n) in an order where
// every column comes before its ancestors, and returns top. mark: n entries, set to k on visit.
int row_pattern(const Pattern& upper, int k, const std::vector<int>& parent,
                std::vector<int>& mark, std::vector<int>& stack) {
  const int n = upper.n;
  int top = n;
  mark[k] = k;
  for (int p = upper.col_start[k]; p < upper.col_start[k + 1]; ++p) {
    int i = upper.row_index[p];
    int length = 0;
    // Walk up until a marked node; the path is pushed in reverse onto the top of the stack.
    for (; mark[i] != k; i = parent[i]) {
      stack[length++] = i;
      mark[i] = k;
    }
    while (length > 0) stack[--top] = stack[--length];
  }
  return top;
}

}  // namespace

void factorize_up_looking(const Pattern& upper, const double* values,
                          const std::vector<int>& parent,
                          const std::vector<int>& original_column, SimplicialFactor& l) {
  const int n = upper.n;
  std::vector<int> next(l.col_start.begin(), l.col_start.end() - 1);  // next free slot per column
  std::vector<int> mark(n, -1), stack(n);
  std::vector<double> x(n, 0.0);  // dense row k of A, then of L
  for (int k = 0; k < n; ++k) {
    const int top = row_pattern(upper, k, parent, mark, stack);
    for (int p = upper.col_start[k]; p < upper.col_start[k + 1]; ++p)
      x[upper.row_index[p]] += values[p];
    double diagonal = x[k];
    x[k] = 0.0;
    for (int t = top; t < n; ++t) {
      const int j = stack[t];
      // L(k, j) = (A(k, j) - sum_{q<j} L(k, q) L(j, q)) / L(j, j); x[j] holds the numerator.
      const double lkj = x[j] / l.values[l.col_start[j]];
      x[j] = 0.0;
      for (int p = l.col_start[j] + 1; p < next[j]; ++p) x[l.row_index[p]] -= l.values[p] * lkj;
      diagonal -= lkj * lkj;
      const int slot = next[j]++;
      l.row_index[slot] = k;
      l.values[slot] = lkj;
    }
    if (!(diagonal > 0.0))
      throw NotPositiveDefinite("SparseCholesky: matrix is not positive definite (pivot of column " +
                                std::to_string(original_column[k]) + " is " +
                                std::to_string(diagonal) + ")");
    const int slot = next[k]++;
    l.row_index[slot] = k;
    l.values[slot] = std::sqrt(diagonal);
  }
}

void solve_simplicial(const SimplicialFactor& l, double* x, int nrhs) {
  const int n = l.n;
  for (int j = 0; j < n; ++j) {
    double* xj = x + static_cast<size_t>(j) * nrhs;
    const double inv = 1.0 / l.values[l.col_start[j]];
    for (int r = 0; r < nrhs; ++r) xj[r] *= inv;
    for (int p = l.col_start[j] + 1; p < l.col_start[j + 1]; ++p) {
      double* xi = x + static_cast<size_t>(l.row_index[p]) * nrhs;
      const double lij = l.values[p];
      for (int r = 0; r < nrhs; ++r) xi[r] -= lij * xj[r];
    }
  }
  for (int j = n - 1; j >= 0; --j) {
    double* xj = x + static_cast<size_t>(j) * nrhs;
    for (int p = l.col_start[j] + 1; p < l.col_start[j + 1]; ++p) {
      const double* xi = x + static_cast<size_t>(l.row_index[p]) * nrhs;
      const double lij = l.values[p];
      for (int r = 0; r < nrhs; ++r) xj[r] -= lij * xi[r];
    }
    const double inv = 1.0 / l.values[l.col_start[j]];
    for (int r = 0; r < nrhs; ++r) xj[r] *= inv;
  }
}

}  // namespace meshik::sparse
