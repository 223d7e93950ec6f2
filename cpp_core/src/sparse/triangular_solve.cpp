#include "sparse/triangular_solve.h"

#include <algorithm>
#include <type_traits>

#include "sparse/simd.h"

namespace meshik::sparse {

namespace {

// The passes work on P::kCount vectors of P::kWidth right-hand sides at a time (P a Pack), so each
// row's values live in registers; x points at the chunk's first column and rows of x are `stride`
// apart. Several rows (forward) or columns (backward) are carried together so that independent
// multiply-adds hide each other's latency and every row of x is loaded once per group.

// V vectors of type T (kWidth doubles each) per row.
template <class T, int V>
struct Pack {
  using Type = T;
  static constexpr int kCount = V;
  static constexpr int kWidth = sizeof(T) / sizeof(double);
  // All lanes equal to a.
  static T broadcast(double a) {
    if constexpr (std::is_same_v<T, Vec>) return sparse::broadcast(a);
    else return a - T{};  // exact: a - 0 is a, signed zeros included
  }
};

// V whole vectors; one half vector (at most kLanes / 2 right-hand sides, which a whole vector
// would carry with as many padding lanes: on AVX-512 machines that split it, twice the work).
template <int V>
using Whole = Pack<Vec, V>;
using Half = Pack<HalfVec, 1>;

// B rows of P::kCount vectors each.
template <class P, int B>
struct Rows {
  static constexpr int V = P::kCount;
  typename P::Type v[B][V];
  void load_from(double* const* p) {
    for (int b = 0; b < B; ++b)
      for (int c = 0; c < V; ++c) v[b][c] = load<typename P::Type>(p[b] + c * P::kWidth);
  }
  void store_to(double* const* p) const {
    for (int b = 0; b < B; ++b)
      for (int c = 0; c < V; ++c) store(p[b] + c * P::kWidth, v[b][c]);
  }
  // every row *= a
  void scale(double a) {
    const typename P::Type s = P::broadcast(a);
    for (int b = 0; b < B; ++b)
      for (int c = 0; c < V; ++c) v[b][c] *= s;
  }
  // row b -= a[b] * x for every b
  void subtract_scaled(const double* a, const double* x) {
    typename P::Type xv[V];
    for (int c = 0; c < V; ++c) xv[c] = load<typename P::Type>(x + c * P::kWidth);
    for (int b = 0; b < B; ++b) {
      const typename P::Type s = P::broadcast(a[b]);
      for (int c = 0; c < V; ++c) v[b][c] = subtract_product(v[b][c], s, xv[c]);
    }
  }
};

// Solves L11 y = x_s in place for the supernode's k consecutive rows xs (L11: the top of the
// column-major block, leading dimension r), row by row.
template <class P>
void diagonal_forward(const double* block, int k, int r, double* xs, long stride) {
  for (int i = 0; i < k; ++i) {
    double* xi = xs + i * stride;
    Rows<P, 1> acc;
    acc.load_from(&xi);
    for (int j = 0; j < i; ++j) {
      const double* lj = block + static_cast<long>(j) * r + i;
      prefetch_rows_ahead(lj);
      acc.subtract_scaled(lj, xs + j * stride);
    }
    acc.scale(1.0 / block[static_cast<long>(i) * r + i]);
    acc.store_to(&xi);
  }
}

// Solves L11^T y = x_s in place (see diagonal_forward), from the last row up.
template <class P>
void diagonal_backward(const double* block, int k, int r, double* xs, long stride) {
  for (int j = k - 1; j >= 0; --j) {
    const double* lj = block + static_cast<long>(j) * r;
    double* xj = xs + j * stride;
    Rows<P, 1> acc;
    acc.load_from(&xj);
    for (int i = j + 1; i < k; ++i) acc.subtract_scaled(lj + i, xs + i * stride);
    acc.scale(1.0 / lj[j]);
    acc.store_to(&xj);
  }
}

// x_{rows[i + b]} -= L(i + b, :) y_s for b < B (L: block, k columns, leading dimension r).
template <class P, int B>
void update_rows_below(const double* block, int k, int r, int i, const int* rows, const double* xs,
                       double* x, long stride) {
  double* xi[B];
  for (int b = 0; b < B; ++b) xi[b] = x + rows[i + b] * stride;
  Rows<P, B> acc;
  acc.load_from(xi);
  for (int j = 0; j < k; ++j) {
    const double* lj = block + static_cast<long>(j) * r + i;
    prefetch_rows_ahead(lj);
    acc.subtract_scaled(lj, xs + j * stride);
  }
  acc.store_to(xi);
}

// x_{j + b} -= sum over the rows i below the supernode of L(i, j + b) x_{rows[i]}, b < B.
template <class P, int B>
void update_from_rows_below(const double* block, int k, int r, int j, const int* rows, double* xs,
                            const double* x, long stride) {
  double* xj[B];
  const double* lj[B];
  for (int b = 0; b < B; ++b) {
    xj[b] = xs + (j + b) * stride;
    lj[b] = block + static_cast<long>(j + b) * r;
  }
  Rows<P, B> acc;
  acc.load_from(xj);
  for (int i = k; i < r; ++i) {
    double l[B];
    for (int b = 0; b < B; ++b) l[b] = lj[b][i];
    acc.subtract_scaled(l, x + rows[i] * stride);
  }
  acc.store_to(xj);
}

// Rows (forward) or columns (backward) carried together with pack P: as many as keep their
// P::kCount accumulators each, one row of x and a broadcast in the target's vector registers (more
// would spill the accumulators to the stack on every multiply-add), at most 8.
template <class P>
constexpr int group_size() {
  return std::clamp((kVectorRegisters - P::kCount - 1) / P::kCount, 1, 8);
}

// Calls work(std::integral_constant<int, B>()) for B = count when 1 <= count <= Max; nothing for
// count 0 (no rows or columns left).
template <int Max, class Work>
void with_count(int count, Work&& work) {
  if (count == Max) work(std::integral_constant<int, Max>());
  else if constexpr (Max > 1) with_count<Max - 1>(count, work);
}

// Forward pass over the simplicial prefix for one chunk: x_u /= L(u, u), then
// x_r -= L(r, u) x_u for its rows r.
template <class P>
void prefix_forward(const SimplicialPrefix& p, const FactorValues& factor, double* x, long stride) {
  for (int u = 0; u < p.size; ++u) {
    double* xu = x + u * stride;
    Rows<P, 1> acc;
    acc.load_from(&xu);
    acc.scale(1.0 / factor.prefix_diagonal[u]);
    acc.store_to(&xu);
    for (int t = p.row_start[u]; t < p.row_start[u + 1]; ++t) {
      double* xr = x + p.rows[t] * stride;
      Rows<P, 1> row;
      row.load_from(&xr);
      row.subtract_scaled(&factor.prefix_below[t], xu);
      row.store_to(&xr);
    }
  }
}

// Backward pass over the simplicial prefix (last column first) for one chunk:
// x_u = (x_u - sum_r L(r, u) x_r) / L(u, u).
template <class P>
void prefix_backward(const SimplicialPrefix& p, const FactorValues& factor, const Reach* reach, double* x,
                     long stride) {
  for (int u = p.size - 1; u >= 0; --u) {
    if (reach != nullptr && !reach->row[u]) continue;
    double* xu = x + u * stride;
    Rows<P, 1> acc;
    acc.load_from(&xu);
    for (int t = p.row_start[u]; t < p.row_start[u + 1]; ++t)
      acc.subtract_scaled(&factor.prefix_below[t], x + p.rows[t] * stride);
    acc.scale(1.0 / factor.prefix_diagonal[u]);
    acc.store_to(&xu);
  }
}

// x_{rows[i]} -= L(i, :) y_s for the rows i in [begin, end) below the diagonal block (begin >= k):
// in groups of group_size<P>() rows (each x_s row loaded once per group), then the rest.
template <class P>
void update_row_range(const double* block, int k, int r, int begin, int end, const int* rows, const double* xs,
                      double* x, long stride) {
  constexpr int B = group_size<P>();
  int i = begin;
  for (; i + B <= end; i += B) update_rows_below<P, B>(block, k, r, i, rows, xs, x, stride);
  if constexpr (B > 1)
    with_count<B - 1>(end - i, [&](auto count) {
      update_rows_below<P, decltype(count)::value>(block, k, r, i, rows, xs, x, stride);
    });
}

// Forward pass over the rows [begin, end) of supernode s (indices among its r rows) for one
// chunk: with begin = 0 its diagonal block first (its own k rows), then the updates of the rows
// below in the range.
template <class P>
void forward_supernode(const SymbolicFactor& f, const double* values, int s, int begin, int end, double* x,
                       long stride) {
  const int k = f.first_column[s + 1] - f.first_column[s];
  const int r = f.row_start[s + 1] - f.row_start[s];
  const double* block = values + f.value_start[s];
  double* xs = x + f.first_column[s] * stride;  // the supernode's k rows are consecutive
  if (begin == 0) diagonal_forward<P>(block, k, r, xs, stride);
  update_row_range<P>(block, k, r, std::max(begin, k), end, f.rows.data() + f.row_start[s], xs, x, stride);
}

// Backward pass over supernode s for one chunk: its rows of x from the rows below (done before).
template <class P>
void backward_supernode(const SymbolicFactor& f, const double* values, int s, double* x, long stride) {
    const int k = f.first_column[s + 1] - f.first_column[s];
    const int r = f.row_start[s + 1] - f.row_start[s];
    const int* rows = f.rows.data() + f.row_start[s];
    const double* block = values + f.value_start[s];
    double* xs = x + f.first_column[s] * stride;
    constexpr int B = group_size<P>();
    int j = 0;  // columns in groups of B (each row below loaded once per group), then the rest
    for (; j + B <= k; j += B) update_from_rows_below<P, B>(block, k, r, j, rows, xs, x, stride);
    if constexpr (B > 1)
      with_count<B - 1>(k - j, [&](auto count) {
        update_from_rows_below<P, decltype(count)::value>(block, k, r, j, rows, xs, x, stride);
      });
    diagonal_backward<P>(block, k, r, xs, stride);
}

// Backward pass (supernodes from the last, then the prefix) for one chunk; with a reach, only
// over its part. With team > 1: the schedule's top first, then its subtrees on the team's
// threads (each supernode's arithmetic is the same whichever thread does it).
template <class P>
void backward_chunk(const Analysis& analysis, const FactorValues& factor, const Reach* reach, double* x,
                    long stride, const SubtreeSchedule* schedule, int team) {
  const SymbolicFactor& f = analysis.symbolic;
  const double* values = factor.supernodal.data();
  auto pass = [&](int s) {
    if (reach == nullptr || reach->supernode[s]) backward_supernode<P>(f, values, s, x, stride);
  };
  if (schedule == nullptr || team <= 1 || schedule->root.size() < 2) {
    for (int s = f.num_supernodes() - 1; s >= 0; --s) pass(s);
  } else {
    for (auto s = schedule->top.rbegin(); s != schedule->top.rend(); ++s) pass(*s);
    const int subtrees = static_cast<int>(schedule->root.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
    for (int t = 0; t < subtrees; ++t)
      for (int s = schedule->root[t]; s >= schedule->first[t]; --s) pass(s);
  }
  prefix_backward<P>(analysis.prefix, factor, reach, x, stride);
}

// Most vectors per chunk: 16 right-hand sides.
constexpr int kMaxVectors = 16 / kLanes;

// Calls work(P()) for a chunk's pack: Half when `half`, else Whole<vectors> (1 <= vectors <= V).
template <int V = kMaxVectors, class Work>
void with_pack(bool half, int vectors, Work&& work) {
  if (half) work(Half());
  else if (vectors == V) work(Whole<V>());
  else if constexpr (V > 1) with_pack<V - 1>(false, vectors, work);
}

// Whether `columns` right-hand sides fit in half a vector (and the target has such halves).
bool fits_half(int columns) { return kLanes >= 4 && columns <= kHalfLanes; }

// Runs pass(P(), xc) on chunks of at most kMaxVectors vectors covering the first `columns` of each
// row (one half vector when they fit in it, else whole vectors), xc the chunk's first column.
// With column_team > 1, on groups of fewer vectors, one thread per group (each column's arithmetic
// is the same in any group, so the result is the same bits).
template <class Pass>
void by_chunks(double* x, int columns, int column_team, Pass&& pass) {
  const bool half = fits_half(columns);
  const int vectors = round_up_to_lanes(columns) / kLanes;
  const int per_group = std::max(1, std::min(kMaxVectors, (vectors + column_team - 1) / column_team));
  const int groups = (vectors + per_group - 1) / per_group;
  auto run_group = [&](int g) {
    const int first = g * per_group;
    with_pack(half, std::min(per_group, vectors - first), [&](auto pack) { pass(pack, x + first * kLanes); });
  };
  if (column_team > 1 && groups > 1) {
#pragma omp parallel for schedule(static) num_threads(std::min(column_team, groups))
    for (int g = 0; g < groups; ++g) run_group(g);
  } else {
    // No region around the schedule's passes: theirs must be the outermost, whose threads the
    // runtime keeps (a team nested in an inactive region is started afresh on every call).
    for (int g = 0; g < groups; ++g) run_group(g);
  }
}

// Calls work(P(), first) for the chunks of at most kMaxVectors vectors that cover the vectors
// [begin, end) of a row (one half vector when `half`), first: the chunk's first vector.
template <class Work>
void for_each_chunk(bool half, int begin, int end, Work&& work) {
  for (int first = begin; first < end; first += kMaxVectors)
    with_pack(half, std::min(kMaxVectors, end - first), [&](auto pack) { work(pack, first); });
}

// The forward pass (prefix, then supernodes) on one thread over the vectors [begin, end) of every
// row: each supernode takes every chunk of them in turn, so that its block comes from memory once
// and from the cache for the other chunks.
void forward_vectors(const Analysis& analysis, const FactorValues& factor, double* x, long stride, bool half,
                     int begin, int end) {
  for_each_chunk(half, begin, end, [&](auto pack, int first) {
    prefix_forward<decltype(pack)>(analysis.prefix, factor, x + first * kLanes, stride);
  });
  const SymbolicFactor& f = analysis.symbolic;
  for (int s = 0; s < f.num_supernodes(); ++s)
    for_each_chunk(half, begin, end, [&](auto pack, int first) {
      forward_supernode<decltype(pack)>(f, factor.supernodal.data(), s, 0, f.row_start[s + 1] - f.row_start[s],
                                        x + first * kLanes, stride);
    });
}

// The forward pass on `team` threads over the schedule's subtrees: the prefix, then in one
// parallel region each subtree's own rows on one thread (all columns, each supernode taking every
// chunk in turn) and the top pass with the vectors in groups, one thread per group. Every row of x
// sees the same operations in the same order as in forward_vectors (a top row's updates in
// increasing supernode order, in the top pass), so the result is the same bits.
void forward_by_subtrees(const Analysis& a, const FactorValues& factor, const SubtreeSchedule& schedule, double* x,
                         int stride, int columns, int team) {
  const SymbolicFactor& f = a.symbolic;
  const double* values = factor.supernodal.data();
  const bool half = fits_half(columns);
  const int vectors = round_up_to_lanes(columns) / kLanes;
  const int subtrees = static_cast<int>(schedule.root.size());
  const int per_group = (vectors + team - 1) / team;
  const int groups = (vectors + per_group - 1) / per_group;
  for_each_chunk(half, 0, vectors, [&](auto pack, int first) {
    prefix_forward<decltype(pack)>(a.prefix, factor, x + first * kLanes, stride);
  });
#pragma omp parallel num_threads(team)
  {
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < subtrees; ++t)
      for (int s = schedule.first[t]; s <= schedule.root[t]; ++s)
        for_each_chunk(half, 0, vectors, [&](auto pack, int first) {
          forward_supernode<decltype(pack)>(f, values, s, 0, schedule.top_row[s], x + first * kLanes, stride);
        });
    // (the loop's barrier: every subtree done before the top pass)
#pragma omp for schedule(static)
    for (int g = 0; g < groups; ++g)
      for (int s : schedule.top_pass)
        for_each_chunk(half, g * per_group, std::min((g + 1) * per_group, vectors), [&](auto pack, int first) {
          forward_supernode<decltype(pack)>(f, values, s, schedule.top_row[s], f.row_start[s + 1] - f.row_start[s],
                                            x + first * kLanes, stride);
        });
  }
}

}  // namespace

void forward_solve(const Analysis& analysis, const FactorValues& factor, double* x, int stride,
                   int columns, int team, const SubtreeSchedule* schedule) {
  if (columns <= 0) return;
  if (schedule != nullptr && team > 1 && schedule->root.size() >= 2) {
    forward_by_subtrees(analysis, factor, *schedule, x, stride, columns, team);
    return;
  }
  // Without a schedule: the vectors in groups, one thread per group.
  const bool half = fits_half(columns);
  const int vectors = round_up_to_lanes(columns) / kLanes;
  if (team <= 1 || vectors < 2) {
    forward_vectors(analysis, factor, x, stride, half, 0, vectors);
    return;
  }
  const int per_group = (vectors + team - 1) / team;
  const int groups = (vectors + per_group - 1) / per_group;
#pragma omp parallel for schedule(static) num_threads(groups)
  for (int g = 0; g < groups; ++g)
    forward_vectors(analysis, factor, x, stride, half, g * per_group, std::min((g + 1) * per_group, vectors));
}

void backward_solve(const Analysis& analysis, const FactorValues& factor, double* x, int stride,
                    int columns, int team, const SubtreeSchedule* schedule) {
  by_chunks(x, columns, schedule == nullptr ? team : 1, [&](auto pack, double* xc) {
    backward_chunk<decltype(pack)>(analysis, factor, nullptr, xc, stride, schedule, schedule == nullptr ? 1 : team);
  });
}

Reach reach_to_roots(const Analysis& analysis, const std::vector<int>& rows) {
  const SimplicialPrefix& p = analysis.prefix;
  const SymbolicFactor& f = analysis.symbolic;
  Reach reach;
  reach.row.assign(analysis.perm.size(), 0);
  reach.supernode.assign(f.num_supernodes(), 0);
  for (int r : rows) reach.row[r] = 1;
  // A reached column's rows below are reached (they come later, so one pass in order suffices).
  for (int u = 0; u < p.size; ++u)
    if (reach.row[u])
      for (int t = p.row_start[u]; t < p.row_start[u + 1]; ++t) reach.row[p.rows[t]] = 1;
  for (int s = 0; s < f.num_supernodes(); ++s) {
    for (int j = f.first_column[s]; j < f.first_column[s + 1] && !reach.supernode[s]; ++j)
      reach.supernode[s] = reach.row[j];
    if (!reach.supernode[s]) continue;
    for (int j = f.first_column[s]; j < f.first_column[s + 1]; ++j) reach.row[j] = 1;
    for (int t = f.row_start[s]; t < f.row_start[s + 1]; ++t) reach.row[f.rows[t]] = 1;
  }
  return reach;
}

void backward_solve(const Analysis& analysis, const FactorValues& factor, const Reach& reach, double* x,
                    int stride, int columns, int team, const SubtreeSchedule* schedule) {
  by_chunks(x, columns, schedule == nullptr ? team : 1, [&](auto pack, double* xc) {
    backward_chunk<decltype(pack)>(analysis, factor, &reach, xc, stride, schedule, schedule == nullptr ? 1 : team);
  });
}

}  // namespace meshik::sparse
