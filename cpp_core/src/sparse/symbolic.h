// The symbolic supernodal factor: per supernode its columns, its row indices and where its
// dense block of values lives, plus the supernodal tree and the multifrontal stack size.
#pragma once

#include <cstddef>
#include <vector>

#include "sparse/pattern.h"
#include "sparse/supernodes.h"

namespace meshik::sparse {

// Supernode s owns columns first_column[s] .. first_column[s+1]-1 (k of them) and the rows
// rows[row_start[s] .. row_start[s+1]) (r of them): first its own k columns in order, then the
// rows below, increasing. Its values are an r by k column-major block at value_start[s]
// (the part above the diagonal of the leading k by k block is unused).
struct SymbolicFactor {
  int n = 0;
  std::vector<int> first_column;       // #S + 1
  std::vector<int> row_start;          // #S + 1
  std::vector<int> rows;               // sum of r
  std::vector<size_t> value_start;     // #S + 1
  std::vector<int> parent;             // #S: supernode holding the first row below s, or -1
  std::vector<int> child_start;        // #S + 1 offsets into children
  std::vector<int> children;           // the children of each supernode, increasing
  std::vector<int> supernode_of;       // n: the supernode owning each column
  size_t stack_size = 0;               // doubles needed by the multifrontal update stack
  int num_supernodes() const { return static_cast<int>(parent.size()); }
  long long structural_nonzeros = 0;   // nnz(L) without explicit zeros, diagonal included
};

// lower: the lower triangle of the postordered, permuted matrix (column j: rows i >= j)
// partition: its supernodes; counts: its column counts (n entries)
// Returns the symbolic factor.
SymbolicFactor symbolic_factor(const Pattern& lower, const SupernodePartition& partition,
                               const std::vector<int>& counts);

// Size in doubles of the packed lower triangle of an m by m update matrix.
inline size_t packed_size(int m) { return static_cast<size_t>(m) * (m + 1) / 2; }

}  // namespace meshik::sparse
