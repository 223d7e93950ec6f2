#include "sparse/input_check.h"

#include <stdexcept>
#include <string>

namespace meshik::sparse {

namespace {

// Throws std::invalid_argument saying `what`.
[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("SparseCholesky: " + what);
}

// Checks that column j's row indices are sorted, unique, in [0, n) and include j itself.
void check_column(const CscMatrix& a, int j) {
  bool has_diagonal = false;
  for (int p = a.col_start[j]; p < a.col_start[j + 1]; ++p) {
    const int i = a.row_index[p];
    if (i < 0 || i >= a.rows)
      fail("column " + std::to_string(j) + " has row index " + std::to_string(i) +
           " out of range [0, " + std::to_string(a.rows) + ")");
    if (p > a.col_start[j] && i <= a.row_index[p - 1])
      fail("column " + std::to_string(j) + " has unsorted or repeated row index " +
           std::to_string(i));
    has_diagonal |= (i == j);
  }
  if (!has_diagonal) fail("column " + std::to_string(j) + " has no diagonal entry");
}

}  // namespace

void check_lower_input(const CscMatrix& a) {
  if (a.rows != a.cols || a.rows < 0)
    fail("matrix must be square, got " + std::to_string(a.rows) + " x " + std::to_string(a.cols));
  if (a.col_start.size() != static_cast<size_t>(a.cols) + 1)
    fail("col_start has " + std::to_string(a.col_start.size()) + " entries, expected cols + 1 = " +
         std::to_string(a.cols + 1));
  if (a.col_start[0] != 0) fail("col_start[0] must be 0");
  for (int j = 0; j < a.cols; ++j)
    if (a.col_start[j + 1] < a.col_start[j])
      fail("col_start decreases at column " + std::to_string(j));
  if (a.row_index.size() != static_cast<size_t>(a.col_start[a.cols]))
    fail("row_index has " + std::to_string(a.row_index.size()) + " entries, col_start ends at " +
         std::to_string(a.col_start[a.cols]));
  if (!a.values.empty() && a.values.size() != a.row_index.size())
    fail("values has " + std::to_string(a.values.size()) + " entries, row_index has " +
         std::to_string(a.row_index.size()));
  for (int j = 0; j < a.cols; ++j) check_column(a, j);
}

}  // namespace meshik::sparse
