// Supernode partition of a postordered elimination tree: runs of consecutive columns with
// nested structure (fundamental chains), then relaxed amalgamation that merges a supernode
// into its parent when that adds few explicit zeros, so the dense kernels get wider blocks.
#pragma once

#include <vector>

namespace meshik::sparse {

struct SupernodePartition {
  std::vector<int> first_column;  // #S + 1: supernode s owns columns [first_column[s], first_column[s+1])
  std::vector<int> row_count;     // #S: rows stored for the first column of s (its pivot rows included)
};

// parent: elimination tree of a postordered matrix (n entries, parent[j] > j or -1)
// counts: column counts of its Cholesky factor (n entries, diagonal included)
// Returns the partition. Columns j-1 and j share a supernode (before relaxation) when
// parent[j-1] == j and counts[j-1] == counts[j] + 1, i.e. column j-1's structure is
// column j's plus row j-1.
SupernodePartition find_supernodes(const std::vector<int>& parent, const std::vector<int>& counts);

}  // namespace meshik::sparse
