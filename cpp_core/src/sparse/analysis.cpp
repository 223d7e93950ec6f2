#include "sparse/analysis.h"

#include "sparse/column_counts.h"
#include "sparse/ordering.h"
#include "sparse/supernodes.h"
#include "sparse/symmetric_graph.h"

namespace meshik::sparse {

Analysis analyze_pattern(const CscMatrix& a) {
  // Degree 4 covers a 4th-vertex unknown (3 neighbours) with room for one more; larger
  // cliques are rare in meshes and cost more to test.
  constexpr int kMaxSimplicialDegree = 4;
  Analysis analysis;
  const Pattern graph = adjacency_graph(a);
  const std::vector<int> simplicial = simplicial_nodes(graph, kMaxSimplicialDegree);
  const int prefix_size = static_cast<int>(simplicial.size());
  // The rest in minimum-degree order, postordered so that supernodes are runs of consecutive
  // columns, after the simplicial nodes.
  std::vector<char> in_prefix(graph.n, 0);
  for (int v : simplicial) in_prefix[v] = 1;
  const TreeOrder order = postordered_minimum_degree(graph, in_prefix);
  analysis.perm = simplicial;
  analysis.perm.insert(analysis.perm.end(), order.perm.begin(), order.perm.end());
  analysis.lower = permute_lower(a, invert_permutation(analysis.perm));
  analysis.prefix = simplicial_prefix(analysis.lower.pattern, prefix_size);
  const std::vector<int> counts = column_counts(analysis.lower.pattern, prefix_size, order.parent);
  analysis.symbolic = symbolic_factor(PermutedView{graph, order.perm, order.inverse}, order.parent, counts,
                                      find_supernodes(order.parent, counts), prefix_size);
  analysis.factor_nonzeros = analysis.prefix.nonzeros() + analysis.symbolic.structural_nonzeros;
  return analysis;
}

}  // namespace meshik::sparse
