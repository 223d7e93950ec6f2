#include "sparse/analysis.h"

#include "sparse/column_counts.h"
#include "sparse/elimination_tree.h"
#include "sparse/ordering.h"
#include "sparse/supernodes.h"
#include "sparse/symmetric_graph.h"

namespace meshik::sparse {

namespace {

// Supernodal analysis of the graph `reduced` (the matrix without its simplicial nodes):
// minimum-degree order, then a postorder of its elimination tree so that supernodes are runs
// of consecutive columns. Writes the order (in `reduced`'s numbering) to `perm` and returns
// the structure numbered from `column_offset`.
SymbolicFactor supernodal_analysis(const Pattern& reduced, int column_offset, std::vector<int>& perm) {
  const int n = reduced.n;
  const std::vector<int> order = minimum_degree_ordering(reduced);
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

}  // namespace

Analysis analyze_pattern(const CscMatrix& a) {
  // Degree 4 covers a 4th-vertex unknown (3 neighbours) with room for one more; larger
  // cliques are rare in meshes and cost more to test.
  constexpr int kMaxSimplicialDegree = 4;
  Analysis analysis;
  const Pattern graph = adjacency_graph(a);
  const std::vector<int> simplicial = simplicial_nodes(graph, kMaxSimplicialDegree);
  const int prefix_size = static_cast<int>(simplicial.size());
  // The rest: the subgraph induced by the other nodes.
  std::vector<char> in_prefix(graph.n, 0);
  for (int v : simplicial) in_prefix[v] = 1;
  std::vector<int> local(graph.n, -1), rest;
  for (int v = 0; v < graph.n; ++v)
    if (!in_prefix[v]) {
      local[v] = static_cast<int>(rest.size());
      rest.push_back(v);
    }
  std::vector<int> rest_perm;
  if (prefix_size == 0)
    analysis.symbolic = supernodal_analysis(graph, 0, rest_perm);
  else
    analysis.symbolic = supernodal_analysis(induced_subgraph(graph, rest, local), prefix_size, rest_perm);
  analysis.perm = simplicial;
  for (int t : rest_perm) analysis.perm.push_back(rest[t]);
  analysis.lower = permute_lower(a, invert_permutation(analysis.perm));
  analysis.prefix = simplicial_prefix(analysis.lower.pattern, prefix_size);
  analysis.factor_nonzeros = analysis.prefix.nonzeros() + analysis.symbolic.structural_nonzeros;
  return analysis;
}

}  // namespace meshik::sparse
