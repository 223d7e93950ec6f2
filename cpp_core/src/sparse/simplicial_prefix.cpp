#include "sparse/simplicial_prefix.h"

#include <cmath>
#include <stdexcept>

#include "sparse/numeric.h"

namespace meshik::sparse {

namespace {

// Position of entry (row, column), row >= column, in the lower triangle; it must exist.
int position_of(const Pattern& lower, int row, int column) {
  for (int p = lower.col_start[column]; p < lower.col_start[column + 1]; ++p)
    if (lower.row_index[p] == row) return p;
  throw std::logic_error("SparseCholesky: simplicial node without a clique of neighbours");
}

}  // namespace

SimplicialPrefix simplicial_prefix(const Pattern& lower, int size) {
  SimplicialPrefix prefix;
  prefix.size = size;
  prefix.diagonal.resize(size);
  prefix.row_start.assign(1, 0);
  prefix.update_start.assign(1, 0);
  for (int u = 0; u < size; ++u) {
    for (int p = lower.col_start[u]; p < lower.col_start[u + 1]; ++p) {
      if (lower.row_index[p] == u) {
        prefix.diagonal[u] = p;
      } else {
        prefix.rows.push_back(lower.row_index[p]);
        prefix.below.push_back(p);
      }
    }
    const int begin = prefix.row_start.back(), end = static_cast<int>(prefix.rows.size());
    for (int s = begin; s < end; ++s)
      for (int t = begin; t <= s; ++t) {
        const int a = prefix.rows[s], b = prefix.rows[t];
        prefix.update.push_back(a >= b ? position_of(lower, a, b) : position_of(lower, b, a));
      }
    prefix.row_start.push_back(end);
    prefix.update_start.push_back(static_cast<int>(prefix.update.size()));
  }
  return prefix;
}

void eliminate_prefix(const SimplicialPrefix& prefix, std::vector<double>& lower_values,
                      const std::vector<int>& original_column, std::vector<double>& diagonal,
                      std::vector<double>& below) {
  diagonal.resize(prefix.size);
  below.resize(prefix.rows.size());
  for (int u = 0; u < prefix.size; ++u) {
    const double pivot = lower_values[prefix.diagonal[u]];
    if (!(pivot > 0.0)) throw_not_positive_definite(original_column[u]);
    const double d = std::sqrt(pivot);
    diagonal[u] = d;
    const int begin = prefix.row_start[u], end = prefix.row_start[u + 1];
    for (int s = begin; s < end; ++s) below[s] = lower_values[prefix.below[s]] / d;
    const int* update = prefix.update.data() + prefix.update_start[u];
    for (int s = begin; s < end; ++s)
      for (int t = begin; t <= s; ++t) lower_values[*update++] -= below[s] * below[t];
  }
}

}  // namespace meshik::sparse
