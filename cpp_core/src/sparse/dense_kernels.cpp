#include "sparse/dense_kernels.h"

#include <algorithm>
#include <cmath>

#include "sparse/simd.h"

namespace meshik::sparse {

namespace {

// kLanes doubles from p when Full, else the first `count` (the rest zero).
template <bool Full>
Vec load_rows(const double* p, int count) {
  if constexpr (Full) return load(p);
  else return load_first(p, count);
}

// Lower products S(p, q) = sum_t A(p, t) A(q, t) over the t < width columns of the
// column-major A (leading dimension ld), computed in tiles of kLanes rows by NC columns and
// handed to an output policy: out(q, p0, acc, first_lane, count) receives rows
// p0 + first_lane .. p0 + count - 1 of column q (those on or below the diagonal).

// One tile: rows p0 .. p0+count-1 (count == kLanes when Full) of columns q0 .. q0+NC-1.
template <int NC, bool Full, class Out>
void product_tile(const double* a, int ld, int width, int q0, int p0, int count, Out& out) {
  Vec acc[NC] = {};
  for (int t = 0; t < width; ++t) {
    const double* at = a + static_cast<long>(t) * ld;
    const Vec column = load_rows<Full>(at + p0, count);
    for (int c = 0; c < NC; ++c) acc[c] += column * broadcast(at[q0 + c]);
  }
  for (int c = 0; c < NC; ++c) {
    const int first_lane = std::max(q0 + c - p0, 0);
    if (first_lane < count) out(q0 + c, p0, acc[c], first_lane, count);
  }
}

// Two full tiles at once (rows p0 .. p0 + 2 kLanes - 1): each loaded scalar serves twice as
// many multiply-adds.
template <int NC, class Out>
void product_double_tile(const double* a, int ld, int width, int q0, int p0, Out& out) {
  Vec upper[NC] = {}, lower[NC] = {};
  for (int t = 0; t < width; ++t) {
    const double* at = a + static_cast<long>(t) * ld;
    prefetch_rows_ahead(at + p0);
    const Vec column_upper = load(at + p0), column_lower = load(at + p0 + kLanes);
    for (int c = 0; c < NC; ++c) {
      const Vec b = broadcast(at[q0 + c]);
      upper[c] += column_upper * b;
      lower[c] += column_lower * b;
    }
  }
  for (int c = 0; c < NC; ++c) {
    const int first_lane = std::max(q0 + c - p0, 0);
    if (first_lane < kLanes) out(q0 + c, p0, upper[c], first_lane, kLanes);
    out(q0 + c, p0 + kLanes, lower[c], std::max(first_lane - kLanes, 0), kLanes);
  }
}

// Columns q0 .. q0+NC-1, rows from the diagonal down to m - 1.
template <int NC, class Out>
void product_columns(const double* a, int ld, int width, int m, int q0, Out& out) {
  int p0 = q0;
  for (; p0 + 2 * kLanes <= m; p0 += 2 * kLanes) product_double_tile<NC>(a, ld, width, q0, p0, out);
  for (; p0 + kLanes <= m; p0 += kLanes) product_tile<NC, true>(a, ld, width, q0, p0, kLanes, out);
  if (p0 < m) product_tile<NC, false>(a, ld, width, q0, p0, m - p0, out);
}

// Columns q_begin .. q_end-1 of the lower product, rows down to m - 1.
template <class Out>
void lower_product(const double* a, int ld, int width, int m, int q_begin, int q_end, Out& out) {
  constexpr int kColumns = 4;  // columns per tile
  int q0 = q_begin;
  for (; q0 + kColumns <= q_end; q0 += kColumns) product_columns<kColumns>(a, ld, width, m, q0, out);
  switch (q_end - q0) {
    case 3: product_columns<3>(a, ld, width, m, q0, out); break;
    case 2: product_columns<2>(a, ld, width, m, q0, out); break;
    case 1: product_columns<1>(a, ld, width, m, q0, out); break;
    default: break;
  }
}

// Output policy: U(p, q) = -S(p, q) into a packed lower triangle (m by m).
struct StoreNegativePacked {
  double* u;
  int m;
  void operator()(int q, int p0, Vec acc, int first_lane, int count) const {
    double* column = u + packed_column_offset(m, q) - q;  // column[p] is U(p, q), p >= q
    if (first_lane == 0 && count == kLanes) store(column + p0, -acc);
    else store_lanes(column + p0, -acc, first_lane, count);
  }
};

// Output policy: U(p, q) -= S(p, q) in a packed lower triangle (m by m).
struct SubtractPacked {
  double* u;
  int m;
  void operator()(int q, int p0, Vec acc, int first_lane, int count) const {
    double* column = u + packed_column_offset(m, q) - q + p0;
    if (first_lane == 0 && count == kLanes) store(column, load(column) - acc);
    else store_lanes(column, load_first(column, count) - acc, first_lane, count);
  }
};

// Output policy: C(p, q) -= S(p, q) in a column-major matrix (leading dimension ld).
struct SubtractColumnMajor {
  double* c;
  int ld;
  void operator()(int q, int p0, Vec acc, int first_lane, int count) const {
    double* column = c + static_cast<long>(q) * ld + p0;
    if (first_lane == 0 && count == kLanes) store(column, load(column) - acc);
    else store_lanes(column, load_first(column, count) - acc, first_lane, count);
  }
};

// cj[p0 .. p0+count) -= sum_{t in [t_begin, j)} ct[p0 .. p0+count) * ct[j] for the columns
// ct of the panel (leading dimension rows); count == kLanes when Full. Each lane's arithmetic is
// the same in a full and a partial tile (explicit fused steps), so a row's result does not depend
// on where the tiles start.
template <bool Full>
void update_column_rows(double* panel, int rows, int t_begin, int j, int p0, int count) {
  double* cj = panel + static_cast<long>(j) * rows;
  Vec sum = load_rows<Full>(cj + p0, count);
  for (int t = t_begin; t < j; ++t) {
    const double* ct = panel + static_cast<long>(t) * rows;
    prefetch_rows_ahead(ct + p0);
    sum = subtract_product(sum, load_rows<Full>(ct + p0, count), broadcast(ct[j]));
  }
  if constexpr (Full) store(cj + p0, sum);
  else store_lanes(cj + p0, sum, 0, count);
}

// Updates rows [row_begin, row_end) of columns j_begin .. j_end-1 of the panel (leading dimension
// rows) with the contributions of columns j_begin .. j-1, left-looking, and scales them by the
// columns' pivots, which the diagonal block already holds (the rows below it, after
// factor_columns factored the block). Each entry gets the arithmetic factor_columns would give it.
void solve_rows(double* panel, int rows, int j_begin, int j_end, int row_begin, int row_end) {
  for (int j = j_begin; j < j_end; ++j) {
    int p0 = row_begin;
    for (; p0 + kLanes <= row_end; p0 += kLanes) update_column_rows<true>(panel, rows, j_begin, j, p0, kLanes);
    if (p0 < row_end) update_column_rows<false>(panel, rows, j_begin, j, p0, row_end - p0);
    double* cj = panel + static_cast<long>(j) * rows;
    const double inverse = 1.0 / cj[j];
    for (int i = row_begin; i < row_end; ++i) cj[i] *= inverse;
  }
}

// Factors columns j_begin .. j_end-1 of the panel (leading dimension rows) left-looking, rows
// from the diagonal down to row_end - 1, their contributions from the columns before j_begin
// being already subtracted. Returns -1 or the first column whose pivot is not positive.
int factor_columns(double* panel, int rows, int j_begin, int j_end, int row_end) {
  for (int j = j_begin; j < j_end; ++j) {
    int p0 = j;
    for (; p0 + kLanes <= row_end; p0 += kLanes) update_column_rows<true>(panel, rows, j_begin, j, p0, kLanes);
    if (p0 < row_end) update_column_rows<false>(panel, rows, j_begin, j, p0, row_end - p0);
    double* cj = panel + static_cast<long>(j) * rows;
    if (!(cj[j] > 0.0)) return j;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inverse = 1.0 / d;
    for (int i = j + 1; i < row_end; ++i) cj[i] *= inverse;
  }
  return -1;
}

// Node-level parallelism: a kernel call of at least kParallelWork multiply-adds runs on the team,
// its columns (or rows) cut into fixed pieces that do not depend on the team's size, each piece
// computed exactly as the serial kernel computes it, so the values are the same bits for any team.
constexpr double kParallelWork = 4e5;
constexpr int kColumnPiece = 16;   // columns per piece of a lower product (a multiple of its tiles' 4)
constexpr int kRowPiece = 256;     // rows per piece of the rows below a block (a multiple of kLanes)

// Whether `work` multiply-adds on `team` threads are worth a parallel region.
bool worth_team(double work, int team) { return team > 1 && work >= kParallelWork; }

// Pieces of `size` in steps of `piece`.
int pieces(int size, int piece) { return (size + piece - 1) / piece; }

}  // namespace

int factor_panel(double* panel, int rows, int cols, int team) {
  // Blocks of kBlock columns: each block is factored left-looking (it stays in cache), then
  // its contribution is subtracted from all later columns at once, so a large panel is
  // streamed once per block instead of once per column. On a team, the block's rows below its
  // diagonal block and the later columns are shared out in pieces.
  constexpr int kBlock = 32;
  for (int j0 = 0; j0 < cols; j0 += kBlock) {
    const int j_end = std::min(j0 + kBlock, cols);
    const int width = j_end - j0;
    const bool split_rows = worth_team(static_cast<double>(rows - j_end) * width * width / 2, team);
    const int failed = factor_columns(panel, rows, j0, j_end, split_rows ? j_end : rows);
    if (failed >= 0) return failed;
    if (split_rows) {
      const int row_pieces = pieces(rows - j_end, kRowPiece);
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
      for (int piece = 0; piece < row_pieces; ++piece) {
        const int row_begin = j_end + piece * kRowPiece;
        solve_rows(panel, rows, j0, j_end, row_begin, std::min(row_begin + kRowPiece, rows));
      }
    }
    if (j_end < cols) {
      SubtractColumnMajor out{panel, rows};
      const double* block = panel + static_cast<long>(j0) * rows;
      const int later = cols - j_end;
      if (worth_team(static_cast<double>(later) * (rows - j_end) * width, team)) {
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
        for (int piece = 0; piece < pieces(later, kColumnPiece); ++piece) {
          const int q_begin = j_end + piece * kColumnPiece;
          lower_product(block, rows, width, rows, q_begin, std::min(q_begin + kColumnPiece, cols), out);
        }
      } else {
        lower_product(block, rows, width, rows, j_end, cols, out);
      }
    }
  }
  return -1;
}

void negative_lower_product(const double* l21, int ld, int m, int k, double* u, int team) {
  // Columns of L21 in chunks that stay in cache while every tile of U is visited; on a team, U's
  // columns in pieces, each visited for every chunk in the same order.
  constexpr int kChunk = 64;
  const auto columns = [&](int q_begin, int q_end) {
    StoreNegativePacked first{u, m};
    lower_product(l21, ld, std::min(k, kChunk), m, q_begin, q_end, first);
    SubtractPacked rest{u, m};
    for (int t0 = kChunk; t0 < k; t0 += kChunk)
      lower_product(l21 + static_cast<long>(t0) * ld, ld, std::min(k - t0, kChunk), m, q_begin, q_end, rest);
  };
  if (!worth_team(static_cast<double>(m) * m * k / 2, team)) {
    columns(0, m);
    return;
  }
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
  for (int piece = 0; piece < pieces(m, kColumnPiece); ++piece) {
    const int q_begin = piece * kColumnPiece;
    columns(q_begin, std::min(q_begin + kColumnPiece, m));
  }
}

}  // namespace meshik::sparse
