// The symbolic supernodal factor: per supernode its columns, its row indices and where its
// dense block of values lives, plus the supernodal tree and the multifrontal stack size.
#pragma once

#include <cstddef>
#include <vector>

#include "sparse/symmetric_graph.h"
#include "sparse/supernodes.h"

namespace meshik::sparse {

// Supernode s owns columns first_column[s] .. first_column[s+1]-1 (k of them) and the rows
// rows[row_start[s] .. row_start[s+1]) (r of them): first its own k columns in order, then the
// rows below, increasing. Its values are an r by k column-major block at value_start[s]
// (the part above the diagonal of the leading k by k block is unused; relaxed supernodes
// also store some explicit zeros).
struct SymbolicFactor {
  int n = 0;
  std::vector<int> first_column;       // #S + 1
  std::vector<int> row_start;          // #S + 1
  std::vector<int> rows;               // sum of r
  std::vector<size_t> value_start;     // #S + 1
  std::vector<int> parent;             // #S: supernode holding the first row below s, or -1
  std::vector<int> child_start;        // #S + 1 offsets into children
  std::vector<int> children;           // the children of each supernode, increasing
  size_t stack_size = 0;               // doubles needed by the multifrontal update stack
  long long structural_nonzeros = 0;   // nnz(L) without explicit zeros, diagonal included
  int num_supernodes() const { return static_cast<int>(parent.size()); }
};

// graph: adjacency of the postordered, permuted matrix; parent: its elimination tree;
// counts: its column counts (n entries each); partition: its supernodes.
// column_offset: columns numbered before these (the simplicial prefix); the result numbers
// columns and rows from it, so that n = column_offset + graph.size().
// Returns the symbolic factor.
SymbolicFactor symbolic_factor(const PermutedView& graph, const std::vector<int>& parent,
                               const std::vector<int>& counts, const SupernodePartition& partition,
                               int column_offset);

// Peak sizes in doubles of the multifrontal update stacks when the supernodes of f are
// processed in order, those of group g (group: #S entries in [0, groups)) on stack g: a
// supernode's update matrix is built on top of its group's stack and stays there until its parent
// takes it when the parent is in the group (else it is held elsewhere, and counts only while it is
// built). Returns #groups sizes; one group gives f.stack_size.
std::vector<size_t> peak_stacks(const SymbolicFactor& f, const std::vector<int>& group, int groups);

// Size in doubles of the packed lower triangle of an m by m update matrix.
inline size_t packed_size(int m) { return static_cast<size_t>(m) * (m + 1) / 2; }

}  // namespace meshik::sparse
