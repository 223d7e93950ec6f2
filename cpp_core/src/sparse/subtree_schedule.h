// Independent subtrees of the supernodal elimination tree, for passes that run them on several
// threads: the numeric factorization and the forward solve handle each subtree on its own, then
// the top of the tree (the ancestors of every subtree); the backward solve the top first, then the
// subtrees. The result is the same bits in any order of the subtrees.
#pragma once

#include <cstddef>
#include <vector>

#include "sparse/symbolic.h"

namespace meshik::sparse {

struct SubtreeSchedule {
  // Supernodes above the subtrees (each an ancestor of some subtree root), increasing.
  std::vector<int> top;
  // Per subtree: its supernodes [first[t], root[t]] (a postorder numbers a subtree
  // consecutively, its root last), largest work first.
  std::vector<int> first;
  std::vector<int> root;
  // Per subtree: the multifrontal update stack (doubles) its factorization needs from empty, its
  // root's update matrix included.
  std::vector<size_t> stack;
  // The top's stack, the subtrees' update matrices held elsewhere.
  size_t top_stack = 0;
  // #S: per supernode, the first of its rows (an index among its r rows) that lies in the top:
  // 0 for a top supernode, at least k for a subtree's. The forward solve updates the rows before
  // it in the subtree's pass, and the rest in the top's.
  std::vector<int> top_row;
  // The supernodes with rows in the top (the top's, and the subtrees' that update top rows),
  // increasing: the forward solve's top pass.
  std::vector<int> top_pass;
};

// f: a symbolic factor whose supernodes are numbered in a postorder of their tree. Splits the
// tree from its roots down, taking the subtree of most work (sum of its supernodes' r k) apart into
// its root (to the top) and its children's subtrees, as many times (at most 512) as minimises the
// estimated time on `threads` (>= 2: the team it is balanced for, e.g. the machine's cores). The
// passes' results never depend on it (nor on the team that runs them), only their speed; a tree
// not in postorder is all top.
SubtreeSchedule subtree_schedule(const SymbolicFactor& f, int threads);

}  // namespace meshik::sparse
