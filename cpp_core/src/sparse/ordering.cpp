#include "sparse/ordering.h"

#include <amd.h>

#include <algorithm>
#include <climits>
#include <memory>
#include <stdexcept>

#include "sparse/breadth_first_order.h"
#include "sparse/elimination_tree.h"

namespace meshik::sparse {

namespace {

// Whether u and v are adjacent (sorted adjacency lists).
bool adjacent(const Pattern& graph, int u, int v) {
  const auto begin = graph.row_index.begin() + graph.col_start[u];
  const auto end = graph.row_index.begin() + graph.col_start[u + 1];
  return std::binary_search(begin, end, v);
}

// graph: as in postordered_minimum_degree; local[v]: node v's index among the m nodes to order
// (increasing with v), or -1 to leave it out. Returns AMD's permutation of the induced subgraph
// (m entries, perm[t] the local index eliminated t-th), AMD given the nodes in the order of
// spread_breadth_first.
// amd_2 orders a graph given in a workspace that it overwrites. amd_order builds exactly this
// input (sorted lists of the symmetric pattern, in node order) after checking and symmetrizing
// the matrix, which the graph already is, so calling amd_2 directly skips that work. The
// workspace's room beyond the lists only sets how often AMD compacts it, and compaction moves
// lists without reordering them: the order is amd_order's (nnz/5 + n of room) with fewer
// compactions (2 nnz + n of room measured 6% faster on the elephant).
std::vector<int> amd_permutation(const Pattern& graph, const std::vector<int>& local, int m) {
  const size_t nnz = graph.row_index.size();
  if (nnz + graph.n >= static_cast<size_t>(INT_MAX))
    throw std::runtime_error("SparseCholesky: matrix too large for the AMD ordering");
  // The induced subgraph in local numbering.
  std::vector<int> induced_start(m + 1, 0), induced;
  induced.reserve(nnz);
  for (int v = 0; v < graph.n; ++v) {
    if (local[v] < 0) continue;
    for (int p = graph.col_start[v]; p < graph.col_start[v + 1]; ++p)
      if (local[graph.row_index[p]] >= 0) induced.push_back(local[graph.row_index[p]]);
    induced_start[local[v] + 1] = static_cast<int>(induced.size());
  }
  std::vector<int> perm(m);
  const int q = static_cast<int>(induced.size());
  if (q == 0) {  // no edges: any order is free of fill (AMD needs at least one)
    for (int t = 0; t < m; ++t) perm[t] = t;
    return perm;
  }
  // AMD's numbering: node order[t] is AMD's node t. Its lists in that numbering, increasing: the
  // graph is symmetric, so going over t in increasing order and appending t to each neighbour's
  // list sorts every list without comparisons.
  const std::vector<int> order = spread_breadth_first(induced_start, induced);
  const std::vector<int> number = invert_permutation(order);
  const size_t room = std::min(2 * nnz + graph.n, static_cast<size_t>(INT_MAX) - 1);
  std::unique_ptr<int[]> workspace(new int[room]);
  std::vector<int> list_start(m), length(m);
  for (int t = 0, at = 0; t < m; ++t) {
    list_start[t] = at;
    length[t] = induced_start[order[t] + 1] - induced_start[order[t]];
    at += length[t];
  }
  std::vector<int> fill(list_start);
  for (int t = 0; t < m; ++t) {
    const int v = order[t];
    for (int p = induced_start[v]; p < induced_start[v + 1]; ++p) workspace[fill[number[induced[p]]]++] = t;
  }
  std::vector<int> amd(m), inverse(m), nv(m), head(m), elen(m), degree(m), w(m);
  double control[AMD_CONTROL];
  amd_defaults(control);
  amd_2(m, list_start.data(), workspace.get(), length.data(), static_cast<int>(room), q, nv.data(),
        inverse.data(), amd.data(), head.data(), elen.data(), degree.data(), w.data(), control, nullptr);
  for (int k = 0; k < m; ++k) perm[k] = order[amd[k]];
  return perm;
}

}  // namespace

std::vector<int> simplicial_nodes(const Pattern& graph, int max_degree) {
  std::vector<int> nodes;
  for (int v = 0; v < graph.n; ++v) {
    const int begin = graph.col_start[v], end = graph.col_start[v + 1];
    if (end - begin > max_degree) continue;
    bool clique = true;
    for (int p = begin; p < end && clique; ++p)
      for (int q = p + 1; q < end && clique; ++q) clique = adjacent(graph, graph.row_index[p], graph.row_index[q]);
    if (clique) nodes.push_back(v);
  }
  return nodes;
}

TreeOrder postordered_minimum_degree(const Pattern& graph, const std::vector<char>& left_out) {
  std::vector<int> local(graph.n), kept;
  for (int v = 0; v < graph.n; ++v) {
    local[v] = left_out[v] ? -1 : static_cast<int>(kept.size());
    if (!left_out[v]) kept.push_back(v);
  }
  const int m = static_cast<int>(kept.size());
  const std::vector<int> amd = amd_permutation(graph, local, m);
  // AMD's order in graph numbering, left-out nodes after every pivot.
  std::vector<int> order(m), order_inverse(graph.n, m);
  for (int k = 0; k < m; ++k) {
    order[k] = kept[amd[k]];
    order_inverse[order[k]] = k;
  }
  const std::vector<int> order_parent = elimination_tree(PermutedView{graph, order, order_inverse});
  const std::vector<int> post = tree_postorder(order_parent);
  TreeOrder result;
  result.perm.resize(m);
  result.inverse.assign(graph.n, m);
  for (int k = 0; k < m; ++k) {
    result.perm[k] = order[post[k]];
    result.inverse[result.perm[k]] = k;
  }
  result.parent = relabel_tree(order_parent, post);
  return result;
}

// Why AMD is given this order: AMD breaks ties between nodes of equal degree by their numbering,
// and the ExampleSet numbers a mesh's vertices breadth first: given that order, its eliminations
// sweep the mesh front by front. Chunks of kSpreadChunk consecutive nodes of a breadth-first order,
// the chunks taken in bit-reversed order of their index, start the eliminations all over the mesh
// instead, and each chunk's lists stay together in memory. The factor's flops (sum over columns of
// their length squared) on the ExampleSets' systems, breadth-first input before and this after: the
// horse subdivided 3 times (1.08M triangles) 10.24 to 7.89 G (stored values 37.7M to 34.1M), the
// elephant subdivided twice 14.13 to 10.98 G, the lion subdivided 3 times 3.81 to 3.19 G, the
// elephant 0.127 to 0.110 G; the horse subdivided twice stayed at 0.84 G. Chunks of 32 to 2,048 all
// gained; 256 was the best or near it on each. The analysis takes 6-11 % longer on those patterns
// (the breadth-first order and the renumbering), and more on a matrix whose own numbering already
// suits AMD (bench/README.md, "AMD's tie-breaks spread over the mesh").
std::vector<int> spread_breadth_first(const std::vector<int>& start, const std::vector<int>& neighbour) {
  const std::vector<int> breadth_first = breadth_first_order(start, neighbour);
  const int n = static_cast<int>(breadth_first.size());
  const int chunks = (n + kSpreadChunk - 1) / kSpreadChunk;
  int bits = 0;
  while ((1 << bits) < chunks) ++bits;
  std::vector<int> order;
  order.reserve(n);
  for (int r = 0; r < (1 << bits); ++r) {
    int chunk = 0;  // r with its `bits` bits reversed
    for (int b = 0; b < bits; ++b) chunk |= ((r >> b) & 1) << (bits - 1 - b);
    if (chunk >= chunks) continue;
    const int end = std::min(n, (chunk + 1) * kSpreadChunk);
    for (int p = chunk * kSpreadChunk; p < end; ++p) order.push_back(breadth_first[p]);
  }
  return order;
}

std::vector<int> invert_permutation(const std::vector<int>& perm) {
  std::vector<int> inverse(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
  return inverse;
}

}  // namespace meshik::sparse
