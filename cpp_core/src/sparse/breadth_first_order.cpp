#include "sparse/breadth_first_order.h"

#include <algorithm>
#include <numeric>

namespace meshik::sparse {

std::vector<int> stable_order_by_key(const std::vector<int>& key, int key_bound) {
  std::vector<int> start(key_bound + 1, 0);
  for (int k : key) ++start[k + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> order(key.size());
  for (size_t i = 0; i < key.size(); ++i) order[start[key[i]]++] = static_cast<int>(i);
  return order;
}

std::vector<int> breadth_first_order(const std::vector<int>& start, const std::vector<int>& neighbour,
                                     std::vector<int>* run_starts) {
  const int n = static_cast<int>(start.size()) - 1;
  std::vector<int> length(n);
  for (int v = 0; v < n; ++v) length[v] = start[v + 1] - start[v];
  const std::vector<int> by_length =
      stable_order_by_key(length, n > 0 ? *std::max_element(length.begin(), length.end()) + 1 : 0);
  std::vector<char> reached(n, 0);
  std::vector<int> order;
  order.reserve(n);
  auto reach = [&](int v) {
    reached[v] = 1;
    order.push_back(v);
  };
  for (int root : by_length) {
    if (reached[root] || length[root] == 0) continue;
    size_t head = order.size();
    if (run_starts != nullptr) run_starts->push_back(static_cast<int>(head));
    reach(root);
    for (; head < order.size(); ++head) {
      const int v = order[head];
      for (int s = start[v]; s < start[v + 1]; ++s)
        if (!reached[neighbour[s]]) reach(neighbour[s]);
    }
  }
  if (run_starts != nullptr) run_starts->push_back(static_cast<int>(order.size()));
  for (int v = 0; v < n; ++v)
    if (!reached[v]) reach(v);
  return order;
}

}  // namespace meshik::sparse
