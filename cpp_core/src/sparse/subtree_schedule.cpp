// Splitting the supernodal tree into a top and independent subtrees of balanced work.
#include "sparse/subtree_schedule.h"

#include <algorithm>

namespace meshik::sparse {

namespace {

constexpr int kMaxSplits = 512;     // supernodes taken apart at most

}  // namespace

SubtreeSchedule subtree_schedule(const SymbolicFactor& f, int threads) {
  const int count = f.num_supernodes();
  // Work and first (lowest) supernode of each subtree; children precede their parent.
  std::vector<double> own(count), work(count);
  std::vector<int> first(count), size(count, 1);
  for (int s = 0; s < count; ++s) {
    own[s] = static_cast<double>(f.row_start[s + 1] - f.row_start[s]) * (f.first_column[s + 1] - f.first_column[s]);
    work[s] += own[s];
    first[s] = s;
    for (int c = f.child_start[s]; c < f.child_start[s + 1]; ++c) first[s] = std::min(first[s], first[f.children[c]]);
    if (f.parent[s] >= 0) {
      work[f.parent[s]] += work[s];
      size[f.parent[s]] += size[s];
    }
  }
  SubtreeSchedule schedule;
  for (int s = 0; s < count; ++s)
    if (size[s] != s - first[s] + 1) {  // not a postorder: everything on top, in one pass
      for (int t = 0; t < count; ++t) schedule.top.push_back(t);
      schedule.top_stack = f.stack_size;
      schedule.top_row.assign(count, 0);
      schedule.top_pass = schedule.top;
      return schedule;
    }
  double total = 0.0;
  std::vector<int> roots;
  for (int s = 0; s < count; ++s)
    if (f.parent[s] < 0) {
      roots.push_back(s);
      total += work[s];
    }
  // Takes the largest subtree apart `splits` times (or until it is a leaf), leaving the subtrees
  // in `subtrees` and the taken roots in `top`. Returns the number of splits (at most `splits`)
  // after which the estimated time on `threads` was least: the top, then the subtrees (at
  // best the rest shared evenly, at worst the largest alone).
  // `subtrees` is kept as a heap whose front is the subtree of most work (of two of equal work,
  // the larger index), so each split costs O(log #subtrees).
  const auto less_work = [&](int a, int b) { return work[a] < work[b] || (work[a] == work[b] && a < b); };
  auto split = [&](int splits, std::vector<int>& top, std::vector<int>& subtrees) {
    subtrees = roots;
    std::make_heap(subtrees.begin(), subtrees.end(), less_work);
    top.clear();
    double top_work = 0.0, best_time = total;
    int best = 0;
    for (int step = 1; step <= splits; ++step) {
      const int s = subtrees.front();
      if (f.child_start[s] == f.child_start[s + 1]) break;
      std::pop_heap(subtrees.begin(), subtrees.end(), less_work);
      subtrees.pop_back();
      top.push_back(s);
      top_work += own[s];
      for (int c = f.child_start[s]; c < f.child_start[s + 1]; ++c) {
        subtrees.push_back(f.children[c]);
        std::push_heap(subtrees.begin(), subtrees.end(), less_work);
      }
      const double largest_work = subtrees.empty() ? 0.0 : work[subtrees.front()];
      const double time = top_work + std::max(largest_work, (total - top_work) / threads);
      if (time < best_time) {
        best_time = time;
        best = step;
      }
    }
    return best;
  };
  std::vector<int> subtrees;
  split(split(std::min(count, kMaxSplits), schedule.top, subtrees), schedule.top, subtrees);
  std::sort(schedule.top.begin(), schedule.top.end());
  std::sort(subtrees.begin(), subtrees.end(), [&](int a, int b) { return less_work(b, a); });
  const int groups = static_cast<int>(subtrees.size());
  std::vector<int> group(count, groups);  // the top is the last group
  for (int t = 0; t < groups; ++t) {
    const int s = subtrees[t];
    schedule.first.push_back(first[s]);
    schedule.root.push_back(s);
    std::fill(group.begin() + first[s], group.begin() + s + 1, t);
  }
  schedule.stack = peak_stacks(f, group, groups + 1);
  schedule.top_stack = schedule.stack.back();
  schedule.stack.pop_back();
  // A subtree's rows end at its root's last column; the rows after it are the top's.
  schedule.top_row.assign(count, 0);
  for (int s = 0; s < count; ++s) {
    if (group[s] < groups) {
      const int root = schedule.root[group[s]];
      const int* rows = f.rows.data() + f.row_start[s];
      const int k = f.first_column[s + 1] - f.first_column[s], r = f.row_start[s + 1] - f.row_start[s];
      schedule.top_row[s] = static_cast<int>(std::upper_bound(rows + k, rows + r, f.first_column[root + 1] - 1) - rows);
    }
    if (schedule.top_row[s] < f.row_start[s + 1] - f.row_start[s]) schedule.top_pass.push_back(s);
  }
  return schedule;
}

}  // namespace meshik::sparse
