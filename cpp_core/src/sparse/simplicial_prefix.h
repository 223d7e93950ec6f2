// The simplicial prefix of the permuted matrix: its first columns are nodes whose neighbours
// are pairwise adjacent (MeshIK's 4th-vertex unknowns, among others). Eliminating such a
// column creates no fill: it only updates entries that exist, so it is done directly on the
// matrix's values before the supernodal factorization of the remaining columns.
#pragma once

#include <vector>

#include "sparse/pattern.h"

namespace meshik::sparse {

// Positions refer to the permuted lower triangle (see PermutedLower).
struct SimplicialPrefix {
  int size = 0;                   // columns 0 .. size-1
  std::vector<int> diagonal;      // size: position of each column's diagonal entry
  std::vector<int> row_start;     // size + 1: offsets into rows / below
  std::vector<int> rows;          // each column's rows below the diagonal
  std::vector<int> below;         // their positions
  std::vector<int> update_start;  // size + 1: offsets into update
  // For column u with rows r_0 .. r_{m-1} (as listed): the positions of the entries
  // (r_s, r_t), t <= s, in the order s = 0..m-1, t = 0..s (larger index first, so that each
  // lies in the lower triangle).
  std::vector<int> update;
  long long nonzeros() const { return size + static_cast<long long>(rows.size()); }
};

// lower: the permuted lower triangle (column j: rows i >= j, diagonal present);
// size: how many leading columns are simplicial nodes. Returns the prefix.
SimplicialPrefix simplicial_prefix(const Pattern& lower, int size);

// Eliminates the prefix columns in place in `lower_values` (the values of the permuted lower
// triangle): L(u, u) = sqrt(A(u, u)), L(r, u) = A(r, u) / L(u, u), then A(r, s) -= L(r, u)
// L(s, u) for every pair of rows. Writes the factor's prefix columns to `diagonal` (size)
// and `below` (prefix.rows.size()). original_column[u] names column u in the error.
// Throws NotPositiveDefinite.
void eliminate_prefix(const SimplicialPrefix& prefix, std::vector<double>& lower_values,
                      const std::vector<int>& original_column, std::vector<double>& diagonal,
                      std::vector<double>& below);

}  // namespace meshik::sparse
