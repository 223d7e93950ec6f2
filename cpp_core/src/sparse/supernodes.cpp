#include "sparse/supernodes.h"

namespace meshik::sparse {

namespace {

// Maximal runs of columns whose structures nest (see find_supernodes). Returns #S + 1 offsets.
std::vector<int> chain_supernodes(const std::vector<int>& parent, const std::vector<int>& counts) {
  const int n = static_cast<int>(parent.size());
  std::vector<int> first(n + 1);
  int chains = 0;
  for (int j = 1; j < n; ++j)
    if (!(parent[j - 1] == j && counts[j - 1] == counts[j] + 1)) first[++chains] = j;
  if (n > 0) first[++chains] = n;
  first.resize(chains + 1);
  return first;
}

// Whether a merged supernode of `columns` columns holding `zeros` explicit zeros among its
// `entries` stored lower-trapezoid entries is acceptable: the wider it is, the fewer zeros.
// Zeros cost work in every solve, narrow blocks cost overhead in the factorization; these
// thresholds were tuned on the elephant and horse normal matrices (bench_cholesky).
bool accept_merge(long long columns, long long zeros, long long entries) {
  const double fraction = static_cast<double>(zeros) / static_cast<double>(entries);
  if (columns <= 4) return fraction < 0.35;
  if (columns <= 16) return fraction < 0.2;
  if (columns <= 48) return fraction < 0.05;
  return fraction < 0.02;
}

}  // namespace

SupernodePartition find_supernodes(const std::vector<int>& parent, const std::vector<int>& counts) {
  const std::vector<int> chains = chain_supernodes(parent, counts);
  const int num_chains = static_cast<int>(chains.size()) - 1;
  // Walk the chains from the last (the roots) to the first. `group_*` describe the merged
  // supernode that currently starts at chain c + 1: its columns, the rows of its first column
  // and its explicit zeros. Chain c merges into it when that group is its parent, i.e. the
  // parent of c's last column is the group's first column.
  std::vector<int> starts_group(num_chains, 1);
  std::vector<long long> group_columns(num_chains), group_rows(num_chains), group_zeros(num_chains);
  for (int c = num_chains - 1; c >= 0; --c) {
    const long long columns = chains[c + 1] - chains[c];
    const long long rows = counts[chains[c]];
    group_columns[c] = columns;
    group_rows[c] = rows;
    group_zeros[c] = 0;
    if (c + 1 == num_chains || parent[chains[c + 1] - 1] != chains[c + 1]) continue;
    // Merged: c's columns grow from `rows` to columns + group_rows[c + 1] rows each.
    const long long merged_columns = columns + group_columns[c + 1];
    const long long merged_rows = columns + group_rows[c + 1];
    const long long merged_zeros = group_zeros[c + 1] + columns * (merged_rows - rows);
    const long long entries = merged_columns * merged_rows - merged_columns * (merged_columns - 1) / 2;
    if (!accept_merge(merged_columns, merged_zeros, entries)) continue;
    starts_group[c + 1] = 0;
    group_columns[c] = merged_columns;
    group_rows[c] = merged_rows;
    group_zeros[c] = merged_zeros;
  }
  SupernodePartition partition;
  partition.first_column.reserve(num_chains + 1);
  partition.row_count.reserve(num_chains);
  for (int c = 0; c < num_chains; ++c)
    if (starts_group[c]) {
      partition.first_column.push_back(chains[c]);
      partition.row_count.push_back(static_cast<int>(group_rows[c]));
    }
  partition.first_column.push_back(static_cast<int>(parent.size()));
  return partition;
}

}  // namespace meshik::sparse
