// A breadth-first (Cuthill-McKee) order of a graph's nodes: neighbours end up close together.
#pragma once

#include <vector>

namespace meshik::sparse {

// The indices 0 .. #key - 1 ordered by key (each in [0, key_bound)), equal keys in index order:
// what std::stable_sort gives, by counting in linear time.
std::vector<int> stable_order_by_key(const std::vector<int>& key, int key_bound);

// start: n + 1 offsets; neighbour: node v's neighbours are neighbour[start[v] .. start[v + 1])
// (repeats allowed). Returns the n nodes in breadth-first order: each component from a node of
// shortest list (ties: the lower node) not yet reached, neighbours in list order; nodes with empty
// lists last, increasing. Each component is one run of the order; with run_starts, the position
// of each run's first node is appended to *run_starts, increasing, then the end of the last run
// (where the nodes with empty lists begin).
std::vector<int> breadth_first_order(const std::vector<int>& start, const std::vector<int>& neighbour,
                                     std::vector<int>* run_starts = nullptr);

}  // namespace meshik::sparse
