#include "sparse/analysis.h"

#include "sparse/column_counts.h"
#include "sparse/elimination_tree.h"
#include "sparse/ordering.h"
#include "sparse/supernodes.h"
#include "sparse/symmetric_graph.h"

namespace meshik::sparse {

namespace {

// Supernodal analysis of the graph `reduced` (the matrix without its simplicial nodes) eliminated
// in `order` (a permutation of its nodes), postordered along its elimination tree so that
// supernodes are runs of consecutive columns. Writes the final order (in `reduced`'s numbering)
// to `perm` and returns the structure numbered from `column_offset`.
SymbolicFactor supernodal_analysis(const Pattern& reduced, const std::vector<int>& order, int column_offset,
                                   std::vector<int>& perm) {
  const int n = reduced.n;
  const Pattern ordered = permuted_graph(reduced, order, invert_permutation(order));
  const std::vector<int> order_parent = elimination_tree(ordered);
  const std::vector<int> post = tree_postorder(order_parent);
  const std::vector<int> order_counts = column_counts(ordered, order_parent, post);
  perm.resize(n);
  std::vector<int> counts(n);
  for (int k = 0; k < n; ++k) {
    perm[k] = order[post[k]];
    counts[k] = order_counts[post[k]];
  }
  const std::vector<int> parent = relabel_tree(order_parent, post);
  return symbolic_factor(permuted_graph(reduced, perm, invert_permutation(perm)), parent, counts,
                         find_supernodes(parent, counts), column_offset);
}

// A matrix's graph split into its simplicial nodes (eliminated first, without fill) and the
// rest, whose induced subgraph the supernodal analysis orders.
struct SplitGraph {
  std::vector<int> simplicial;  // increasing node indices
  std::vector<int> rest;        // the other nodes, increasing
  std::vector<int> local;       // #nodes: index in `rest`, or -1 for a simplicial node
  Pattern reduced;              // the subgraph induced by `rest`, in its numbering
};

SplitGraph split_simplicial(const CscMatrix& a) {
  // Degree 4 covers a 4th-vertex unknown (3 neighbours) with room for one more; larger
  // cliques are rare in meshes and cost more to test.
  constexpr int kMaxSimplicialDegree = 4;
  SplitGraph split;
  const Pattern graph = adjacency_graph(a);
  split.simplicial = simplicial_nodes(graph, kMaxSimplicialDegree);
  std::vector<char> in_prefix(graph.n, 0);
  for (int v : split.simplicial) in_prefix[v] = 1;
  split.local.assign(graph.n, -1);
  for (int v = 0; v < graph.n; ++v)
    if (!in_prefix[v]) {
      split.local[v] = static_cast<int>(split.rest.size());
      split.rest.push_back(v);
    }
  split.reduced = split.simplicial.empty() ? graph : induced_subgraph(graph, split.rest, split.local);
  return split;
}

// The analysis of `a` (split as `split`) with the rest eliminated in rest_order (local indices).
Analysis analysis_in_order(const CscMatrix& a, const SplitGraph& split, const std::vector<int>& rest_order) {
  Analysis analysis;
  const int prefix_size = static_cast<int>(split.simplicial.size());
  std::vector<int> rest_perm;
  analysis.symbolic = supernodal_analysis(split.reduced, rest_order, prefix_size, rest_perm);
  analysis.perm = split.simplicial;
  for (int t : rest_perm) analysis.perm.push_back(split.rest[t]);
  analysis.lower = permute_lower(a, invert_permutation(analysis.perm));
  analysis.prefix = simplicial_prefix(analysis.lower.pattern, prefix_size);
  analysis.factor_nonzeros = analysis.prefix.nonzeros() + analysis.symbolic.structural_nonzeros;
  return analysis;
}

}  // namespace

std::vector<int> fill_reducing_order(const CscMatrix& a) {
  const SplitGraph split = split_simplicial(a);
  std::vector<int> order = split.simplicial;
  for (int t : minimum_degree_ordering(split.reduced)) order.push_back(split.rest[t]);
  return order;
}

Analysis analyze_pattern(const CscMatrix& a) {
  const SplitGraph split = split_simplicial(a);
  return analysis_in_order(a, split, minimum_degree_ordering(split.reduced));
}

Analysis analyze_pattern(const CscMatrix& a, const std::vector<int>& order) {
  const SplitGraph split = split_simplicial(a);
  std::vector<int> rest_order;
  rest_order.reserve(split.rest.size());
  for (int v : order)
    if (split.local[v] >= 0) rest_order.push_back(split.local[v]);
  return analysis_in_order(a, split, rest_order);
}

}  // namespace meshik::sparse
