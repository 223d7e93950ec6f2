// Symbolic analysis (adjacency graph, ordering, elimination tree, postorder, column counts,
// supernodes and their row structures) against a brute-force symbolic elimination on dense
// boolean matrices.
#include <amd.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <random>
#include <vector>

#include "sparse/breadth_first_order.h"
#include "sparse/column_counts.h"
#include "sparse/elimination_tree.h"
#include "sparse/ordering.h"
#include "sparse/permuted_matrix.h"
#include "sparse/supernodes.h"
#include "sparse/symbolic.h"
#include "sparse/symmetric_graph.h"
#include "sparse_test_matrices.h"

using namespace meshik::sparse;
using BoolMatrix = std::vector<std::vector<bool>>;

namespace {

// A random symmetric boolean n by n pattern with the given off-diagonal density, diagonal set.
BoolMatrix random_pattern(int n, double density, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  BoolMatrix a(n, std::vector<bool>(n, false));
  for (int j = 0; j < n; ++j) {
    a[j][j] = true;
    for (int i = j + 1; i < n; ++i) a[i][j] = a[j][i] = coin(rng) < density;
  }
  return a;
}

// The lower triangle of a boolean pattern as a CscMatrix with unit values.
meshik::CscMatrix lower_matrix(const BoolMatrix& a) {
  const int n = static_cast<int>(a.size());
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (a[i][j]) dense(i, j) = 1.0;
  return meshik_test::lower_from_dense(dense);
}

// Structure of L by symbolic elimination: L(i, j) != 0 for i > j iff A(i, j) != 0 or
// L(i, k) and L(j, k) != 0 for some k < j. Returns the n by n boolean lower triangle.
BoolMatrix symbolic_elimination(BoolMatrix l) {
  const int n = static_cast<int>(l.size());
  for (int k = 0; k < n; ++k)
    for (int j = k + 1; j < n; ++j)
      if (l[j][k])
        for (int i = j + 1; i < n; ++i)
          if (l[i][k]) l[i][j] = true;
  return l;
}

// P A P^T of a boolean pattern, perm[k] = old index of new k.
BoolMatrix permuted(const BoolMatrix& a, const std::vector<int>& perm) {
  const int n = static_cast<int>(a.size());
  BoolMatrix c(n, std::vector<bool>(n, false));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) c[i][j] = a[perm[i]][perm[j]];
  return c;
}

std::vector<int> identity(int n) {
  std::vector<int> p(n);
  for (int i = 0; i < n; ++i) p[i] = i;
  return p;
}

// A queue-based breadth-first search written out for the test: roots by shortest list (ties:
// lower node), neighbours in list order, isolated nodes last.
std::vector<int> reference_breadth_first(const std::vector<int>& start, const std::vector<int>& neighbour) {
  const int n = static_cast<int>(start.size()) - 1;
  std::vector<int> roots(n);
  for (int v = 0; v < n; ++v) roots[v] = v;
  std::stable_sort(roots.begin(), roots.end(),
                   [&](int u, int v) { return start[u + 1] - start[u] < start[v + 1] - start[v]; });
  std::vector<bool> seen(n, false);
  std::vector<int> order;
  for (int root : roots) {
    if (seen[root] || start[root + 1] == start[root]) continue;
    std::deque<int> queue{root};
    seen[root] = true;
    while (!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      order.push_back(v);
      for (int s = start[v]; s < start[v + 1]; ++s)
        if (!seen[neighbour[s]]) {
          seen[neighbour[s]] = true;
          queue.push_back(neighbour[s]);
        }
    }
  }
  for (int v = 0; v < n; ++v)
    if (!seen[v]) order.push_back(v);
  return order;
}

}  // namespace

TEST(SparseSymbolic, AdjacencyGraphIsSymmetricAndSorted) {
  const BoolMatrix a = random_pattern(40, 0.15, 3);
  const Pattern g = adjacency_graph(lower_matrix(a));
  for (int v = 0; v < 40; ++v) {
    std::vector<int> expected;
    for (int u = 0; u < 40; ++u)
      if (u != v && a[u][v]) expected.push_back(u);
    EXPECT_EQ(std::vector<int>(g.row_index.begin() + g.col_start[v], g.row_index.begin() + g.col_start[v + 1]),
              expected)
        << "node " << v;
  }
}

TEST(SparseSymbolic, OrderIsAmdOrderOfTheKeptNodesPostordered) {
  unsigned seed = 300;
  for (int n : {1, 7, 60, 200})
    for (double density : {0.0, 0.05, 0.3})
      for (bool leave_some_out : {false, true}) {
        SCOPED_TRACE("n=" + std::to_string(n) + " density=" + std::to_string(density) +
                     " leave_some_out=" + std::to_string(leave_some_out));
        const BoolMatrix a = random_pattern(n, density, seed++);
        std::vector<char> left_out(n, 0);
        std::vector<int> kept;
        for (int v = 0; v < n; ++v) {
          left_out[v] = leave_some_out && v % 4 == 2;
          if (!left_out[v]) kept.push_back(v);
        }
        const int m = static_cast<int>(kept.size());
        // amd_order of the kept nodes' submatrix numbered by spread_breadth_first, then the
        // postorder of its elimination tree.
        BoolMatrix sub(m, std::vector<bool>(m));
        for (int s = 0; s < m; ++s)
          for (int t = 0; t < m; ++t) sub[s][t] = a[kept[s]][kept[t]];
        const meshik::CscMatrix sub_lower = lower_matrix(sub);
        const Pattern sub_graph = adjacency_graph(sub_lower);
        const std::vector<int> spread = spread_breadth_first(sub_graph.col_start, sub_graph.row_index);
        const meshik::CscMatrix spread_lower = lower_matrix(permuted(sub, spread));
        std::vector<int> amd(m);
        double control[AMD_CONTROL];
        amd_defaults(control);
        ASSERT_EQ(
            amd_order(m, spread_lower.col_start.data(), spread_lower.row_index.data(), amd.data(), control, nullptr),
            AMD_OK);
        for (int& node : amd) node = spread[node];
        const std::vector<int> amd_inverse = invert_permutation(amd);
        const std::vector<int> amd_parent = elimination_tree(PermutedView{sub_graph, amd, amd_inverse});
        const std::vector<int> post = tree_postorder(amd_parent);

        const TreeOrder order = postordered_minimum_degree(adjacency_graph(lower_matrix(a)), left_out);
        ASSERT_EQ(order.perm.size(), kept.size());
        for (int k = 0; k < m; ++k) {
          EXPECT_EQ(order.perm[k], kept[amd[post[k]]]) << "pivot " << k;
          EXPECT_EQ(order.inverse[order.perm[k]], k);
        }
        for (int v = 0; v < n; ++v)
          if (left_out[v]) EXPECT_EQ(order.inverse[v], m) << "left-out node " << v;
        EXPECT_EQ(order.parent, relabel_tree(amd_parent, post));
      }
}

TEST(SparseSymbolic, BreadthFirstOrderMatchesAQueue) {
  unsigned seed = 500;
  for (int n : {0, 1, 9, 80, 300})
    for (double density : {0.0, 0.01, 0.05, 0.5}) {
      SCOPED_TRACE("n=" + std::to_string(n) + " density=" + std::to_string(density));
      const Pattern graph = adjacency_graph(lower_matrix(random_pattern(n, density, seed++)));
      EXPECT_EQ(breadth_first_order(graph.col_start, graph.row_index),
                reference_breadth_first(graph.col_start, graph.row_index));
    }
}

TEST(SparseSymbolic, SpreadOrderTakesBreadthFirstChunksInBitReversedOrder) {
  // A path of 1,000 nodes numbered from one end is its own breadth-first order: 4 chunks of 256
  // (the last one short), taken as chunks 0, 2, 1, 3.
  const int n = 1000;
  std::vector<int> start{0}, neighbour;
  for (int v = 0; v < n; ++v) {
    if (v > 0) neighbour.push_back(v - 1);
    if (v + 1 < n) neighbour.push_back(v + 1);
    start.push_back(static_cast<int>(neighbour.size()));
  }
  ASSERT_EQ(kSpreadChunk, 256);
  std::vector<int> expected;
  for (int chunk : {0, 2, 1, 3})
    for (int v = chunk * 256; v < std::min(n, (chunk + 1) * 256); ++v) expected.push_back(v);
  EXPECT_EQ(spread_breadth_first(start, neighbour), expected);
  // One chunk: the breadth-first order itself.
  const Pattern graph = adjacency_graph(lower_matrix(random_pattern(200, 0.03, 9)));
  EXPECT_EQ(spread_breadth_first(graph.col_start, graph.row_index),
            breadth_first_order(graph.col_start, graph.row_index));
}

TEST(SparseSymbolic, EliminationTreeAndCountsMatchBruteForce) {
  unsigned seed = 1;
  for (int n : {1, 2, 5, 12, 40, 90})
    for (double density : {0.0, 0.03, 0.1, 0.4, 1.0}) {
      SCOPED_TRACE("n=" + std::to_string(n) + " density=" + std::to_string(density));
      const BoolMatrix a = random_pattern(n, density, seed++);
      const Pattern graph = adjacency_graph(lower_matrix(a));
      // Under a random permutation, compared with elimination of the permuted pattern.
      std::vector<int> perm = identity(n);
      std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
      const std::vector<int> inverse = invert_permutation(perm);
      const std::vector<int> parent = elimination_tree(PermutedView{graph, perm, inverse});
      // Column counts need a postordered tree: the same permutation followed by the postorder.
      const std::vector<int> post = tree_postorder(parent);
      std::vector<int> post_perm(n);
      for (int k = 0; k < n; ++k) post_perm[k] = perm[post[k]];
      const PermutedLower post_lower = permute_lower(lower_matrix(a), invert_permutation(post_perm));
      const std::vector<int> counts = column_counts(post_lower.pattern, 0, relabel_tree(parent, post));
      const BoolMatrix l = symbolic_elimination(permuted(a, perm));
      const BoolMatrix post_l = symbolic_elimination(permuted(a, post_perm));
      for (int j = 0; j < n; ++j) {
        // parent[j]: the first off-diagonal row of column j of L.
        int first_row = -1, count = 1;
        for (int i = n - 1; i > j; --i)
          if (l[i][j]) first_row = i;
        for (int i = j + 1; i < n; ++i) count += post_l[i][j];
        EXPECT_EQ(parent[j], first_row) << "column " << j;
        EXPECT_EQ(counts[j], count) << "column " << j;
      }
    }
}

TEST(SparseSymbolic, SupernodeRowsMatchBruteForce) {
  unsigned seed = 100;
  for (int n : {1, 3, 20, 60, 150})
    for (double density : {0.0, 0.02, 0.08, 0.3, 1.0}) {
      SCOPED_TRACE("n=" + std::to_string(n) + " density=" + std::to_string(density));
      const BoolMatrix a = random_pattern(n, density, seed++);
      const Pattern graph = adjacency_graph(lower_matrix(a));
      // Postordered fill-reducing order, as SparseCholesky::analyze builds it.
      const TreeOrder order = postordered_minimum_degree(graph, std::vector<char>(n, 0));
      const std::vector<int>& perm = order.perm;
      EXPECT_EQ(order.inverse, invert_permutation(perm));
      const PermutedLower lower = permute_lower(lower_matrix(a), order.inverse);
      const std::vector<int> counts = column_counts(lower.pattern, 0, order.parent);
      const SupernodePartition partition = find_supernodes(order.parent, counts);
      const SymbolicFactor f =
          symbolic_factor(PermutedView{graph, perm, order.inverse}, order.parent, counts, partition, 0);
      std::vector<int> supernode_of(n);
      for (int s = 0; s < f.num_supernodes(); ++s)
        for (int j = f.first_column[s]; j < f.first_column[s + 1]; ++j) supernode_of[j] = s;
      const BoolMatrix l = symbolic_elimination(permuted(a, perm));
      ASSERT_EQ(f.first_column.back(), n);
      for (int s = 0; s < f.num_supernodes(); ++s) {
        const int first = f.first_column[s], end = f.first_column[s + 1];
        ASSERT_LT(first, end);
        // Stored rows: the supernode's columns, then the union of its columns' rows below it.
        std::vector<int> expected;
        for (int j = first; j < end; ++j) expected.push_back(j);
        for (int i = end; i < n; ++i) {
          bool any = false;
          for (int j = first; j < end; ++j) any = any || l[i][j];
          if (any) expected.push_back(i);
        }
        EXPECT_EQ(std::vector<int>(f.rows.begin() + f.row_start[s], f.rows.begin() + f.row_start[s + 1]), expected)
            << "supernode " << s;
        // The parent supernode owns the first row below.
        EXPECT_EQ(f.parent[s], expected.size() > static_cast<size_t>(end - first)
                                   ? supernode_of[expected[end - first]]
                                   : -1);
      }
      long long nnz = 0;
      for (int j = 0; j < n; ++j)
        for (int i = j; i < n; ++i) nnz += l[i][j];
      EXPECT_EQ(f.structural_nonzeros, nnz);
    }
}

TEST(SparseSymbolic, SimplicialNodesHaveCliqueNeighbourhoods) {
  // A 4-cycle 0-1-2-3 with chord 0-2; node 4 joined to the triangle 0, 1, 2 and node 5 to
  // the edge 0-3 (simplicial: their neighbours are pairwise adjacent); node 6 joined to 1 and
  // 3, which are not adjacent (not simplicial).
  BoolMatrix a(7, std::vector<bool>(7, false));
  auto edge = [&](int u, int v) { a[u][v] = a[v][u] = true; };
  for (int v = 0; v < 7; ++v) a[v][v] = true;
  edge(0, 1), edge(1, 2), edge(2, 3), edge(3, 0), edge(0, 2);
  edge(4, 0), edge(4, 1), edge(4, 2);
  edge(5, 0), edge(5, 3);
  edge(6, 1), edge(6, 3);
  const Pattern graph = adjacency_graph(lower_matrix(a));
  EXPECT_EQ(simplicial_nodes(graph, 4), (std::vector<int>{4, 5}));
  EXPECT_EQ(simplicial_nodes(graph, 2), (std::vector<int>{5}));
}

TEST(SparseSymbolic, PostorderVisitsDescendantsFirstAndContiguously) {
  // A forest: 0,1 -> 2; 3 -> 4; 2,4 -> 6; 5 alone; 7 -> 8.
  const std::vector<int> parent = {2, 2, 6, 4, 6, -1, -1, 8, -1};
  const std::vector<int> post = tree_postorder(parent);
  ASSERT_EQ(post.size(), parent.size());
  std::vector<int> position(parent.size(), -1);
  for (size_t k = 0; k < post.size(); ++k) {
    ASSERT_EQ(position[post[k]], -1) << "node visited twice";
    position[post[k]] = static_cast<int>(k);
  }
  for (size_t j = 0; j < parent.size(); ++j) {
    if (parent[j] != -1) {
      EXPECT_LT(position[j], position[parent[j]]);
    }
  }
  // The subtree of 6 is {0, 1, 2, 3, 4, 6}: six consecutive positions ending at 6's.
  for (int j : {0, 1, 2, 3, 4}) EXPECT_GE(position[j], position[6] - 5);
  // Relabelled by the postorder, every parent is larger than its child.
  const std::vector<int> relabeled = relabel_tree(parent, post);
  for (size_t k = 0; k < relabeled.size(); ++k) {
    if (relabeled[k] != -1) {
      EXPECT_GT(relabeled[k], static_cast<int>(k));
    }
  }
}
