// The reduced energy, its optimal vertices and its Gauss-Newton system at given weights.
// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 reductions (built with
// -march=native); the values it names are always written first.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "pose_evaluation.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "feature_space.h"
#include "page_arrays.h"
#include "region_outer_products.h"
#include "simd_clones.h"

namespace meshik {

namespace {

constexpr int L = kLanes;

// The passes hand out their chunks (and rows, kRowsPerTask at a time) dynamically: the partition,
// not the schedule, fixes the result, and a thread the system deschedules (the machine's other
// work) then delays its team by one task, not by its whole share.
constexpr int kRowsPerTask = 2048;

// Adds one batch's J^T J (lower triangle, per lane) and J^T F (per lane). out: a blend_batch
// output, or a region batch's (F, then its k Jacobian columns); its column a is column columns[a]
// (ascending) of the K weights: into jtj_lanes (K by K by kLanes) and jtf_lanes (K by kLanes).
MESHIK_SIMD_CLONES
void accumulate_mapped_products(const double* __restrict out, int k, const int* columns, int num_weights,
                                double* __restrict jtj_lanes, double* __restrict jtf_lanes) {
  for (int a = 0; a < k; ++a) {
    const double* __restrict ja = out + (a + 1) * 6 * L;
    const int ca = columns[a];
    double sum[L];
    for (int l = 0; l < L; ++l) sum[l] = jtf_lanes[ca * L + l];
    for (int e = 0; e < 6; ++e)
      for (int l = 0; l < L; ++l) sum[l] += ja[e * L + l] * out[e * L + l];
    for (int l = 0; l < L; ++l) jtf_lanes[ca * L + l] = sum[l];
    for (int b = 0; b <= a; ++b) {
      const double* __restrict jb = out + (b + 1) * 6 * L;
      double* __restrict acc = jtj_lanes + (static_cast<size_t>(ca) * num_weights + columns[b]) * L;
      for (int l = 0; l < L; ++l) sum[l] = acc[l];
      for (int e = 0; e < 6; ++e)
        for (int l = 0; l < L; ++l) sum[l] += ja[e * L + l] * jb[e * L + l];
      for (int l = 0; l < L; ++l) acc[l] = sum[l];
    }
  }
}

// Asks the L2 cache for the rows of rhs (rows of `stride` doubles) that the `count` corners
// will update, ahead of the scatter. rows: the corners' rows (AssemblyPartition::corner_row, -1
// for none); the rows are in the factor's order, so neighbouring triangles' rows are far apart.
// (A read hint into L2 measured faster than a write hint into L1, which competes with the
// features' stream.)
void prefetch_rows(const double* rhs, int stride, const int* rows, int count) {
  constexpr int kLineDoubles = 64 / sizeof(double);
  for (int i = 0; i < count; ++i) {
    if (rows[i] < 0) continue;
    const double* row = rhs + static_cast<size_t>(rows[i]) * stride;
    for (int e = 0; e < stride; e += kLineDoubles) __builtin_prefetch(row + e, 0, 2);
  }
}

// One row of a batch's output block: kLanes values, one per triangle (GCC / Clang vector extension).
typedef double LaneRow __attribute__((vector_size(L * sizeof(double))));
static_assert(L == 8, "transpose_rows is written for batches of 8 triangles");

MESHIK_LANE_INLINE LaneRow load_row(const double* p) {
  LaneRow v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// In place: row i, lane l becomes row l, lane i (an 8 by 8 transpose in registers: three rounds
// of two-input shuffles, no trip through memory).
MESHIK_LANE_INLINE void transpose_rows(LaneRow (&r)[L]) {
  typedef long long Index __attribute__((vector_size(L * sizeof(long long))));
  constexpr Index kEvenPairs = {0, 8, 2, 10, 4, 12, 6, 14}, kOddPairs = {1, 9, 3, 11, 5, 13, 7, 15};
  constexpr Index kLowQuads = {0, 1, 8, 9, 4, 5, 12, 13}, kHighQuads = {2, 3, 10, 11, 6, 7, 14, 15};
  constexpr Index kLowHalves = {0, 1, 2, 3, 8, 9, 10, 11}, kHighHalves = {4, 5, 6, 7, 12, 13, 14, 15};
  LaneRow a[L], b[L];
  for (int i = 0; i < L; i += 2) {
    a[i] = __builtin_shuffle(r[i], r[i + 1], kEvenPairs);
    a[i + 1] = __builtin_shuffle(r[i], r[i + 1], kOddPairs);
  }
  for (int i = 0; i < L; i += 4)
    for (int j = 0; j < 2; ++j) {
      b[i + j] = __builtin_shuffle(a[i + j], a[i + j + 2], kLowQuads);
      b[i + j + 2] = __builtin_shuffle(a[i + j], a[i + j + 2], kHighQuads);
    }
  for (int j = 0; j < 4; ++j) {
    r[j] = __builtin_shuffle(b[j], b[j + 4], kLowHalves);
    r[j + 4] = __builtin_shuffle(b[j], b[j + 4], kHighHalves);
  }
}

// G'^T for one batch: every free corner q of triangle j adds g_q . (row c of each block) to its
// row of rhs (rows of `stride` doubles, layout of PoseEvaluator::rhs_). out: blend_batch's output;
// stride: a multiple of kLanes; source: `stride` entries, for each column of rhs the row of out
// holding its first column (the next row holds the second), or -1 for a padding column (see
// column_sources); lanes: triangles in the batch; rows (lanes by 3): the row of rhs each corner
// adds to (AssemblyPartition::corner_row, -1 for none); gradient (lanes by kGradientEntries): the
// batch's.
// Eight columns at a time, the batch's rows are transposed in registers, so that each triangle's
// values are one vector per column block.
MESHIK_SIMD_CLONES
void scatter_batch(const double* out, const int* source, int stride, int lanes, const int* rows,
                   const double* gradient, double* rhs) {
  for (int block = 0; block < stride; block += L) {
    bool empty = true;  // only padding columns (regions: columns of regions the batch lacks)
    for (int i = 0; i < L; ++i) empty = empty && source[block + i] < 0;
    if (empty) continue;
    LaneRow first[L], second[L];
    for (int i = 0; i < L; ++i) {
      const int e = source[block + i];
      first[i] = e < 0 ? LaneRow{} : load_row(out + e * L);
      second[i] = e < 0 ? LaneRow{} : load_row(out + (e + 1) * L);
    }
    transpose_rows(first);
    transpose_rows(second);
    for (int l = 0; l < lanes; ++l) {
      double g[6];
      corner_gradients(gradient + kGradientEntries * l, g);
      for (int q = 0; q < 3; ++q) {
        const int u = rows[3 * l + q];
        if (u < 0) continue;
        double* row = rhs + static_cast<size_t>(u) * stride + block;
        const LaneRow sum = load_row(row) + g[2 * q] * first[l] + g[2 * q + 1] * second[l];
        std::memcpy(row, &sum, sizeof sum);
      }
    }
  }
}

// Replaces F_j by R_j = Q_j(x) - F_j in `terms` (the batch's 6 rows of kLanes) for its `lanes`
// triangles, zeroing the padding lanes; returns sum |R_j|^2, and in *inverted bit l set when
// triangle l is turned over against its target: the normal of the posed triangle, Q_j's column 1
// x column 2, points away from F_j's (negative dot product). vertices: #V by 3; triangles /
// gradient: the batch's first triangle's entries.
MESHIK_SIMD_CLONES
double batch_residual(const double* vertices, const int* triangles, const double* gradient,
                      int lanes, double* terms, unsigned* inverted) {
  double posed[6][L] = {};  // Q_j, rows as in terms
  for (int l = 0; l < lanes; ++l) {
    double g[6];
    corner_gradients(gradient + kGradientEntries * l, g);
    const double* x0 = vertices + 3 * static_cast<size_t>(triangles[3 * l]);
    const double* x1 = vertices + 3 * static_cast<size_t>(triangles[3 * l + 1]);
    const double* x2 = vertices + 3 * static_cast<size_t>(triangles[3 * l + 2]);
    for (int c = 0; c < 3; ++c) {
      posed[2 * c][l] = x0[c] * g[0] + x1[c] * g[2] + x2[c] * g[4];
      posed[2 * c + 1][l] = x0[c] * g[1] + x1[c] * g[3] + x2[c] * g[5];
    }
  }
  if (lanes < L)  // only the last batch
    for (int e = 0; e < 6; ++e)
      for (int l = lanes; l < L; ++l) terms[e * L + l] = 0.0;
  double energy = 0.0;
  unsigned mask = 0;
  for (int l = 0; l < L; ++l) {
    const double* t = terms + l;  // F_j: entry (row, column) at t[(2 row + column) L]
    double facing = 0.0;
    for (int c = 0; c < 3; ++c) {
      const int p = (c + 1) % 3, q = (c + 2) % 3;
      const double posed_normal =
          posed[2 * p][l] * posed[2 * q + 1][l] - posed[2 * q][l] * posed[2 * p + 1][l];
      const double target_normal =
          t[2 * p * L] * t[(2 * q + 1) * L] - t[2 * q * L] * t[(2 * p + 1) * L];
      facing += posed_normal * target_normal;
    }
    mask |= facing < 0.0 ? 1u << l : 0u;
  }
  for (int e = 0; e < 6; ++e)
    for (int l = 0; l < L; ++l) {
      const double r = posed[e][l] - terms[e * L + l];
      terms[e * L + l] = r;
      energy += r * r;
    }
  *inverted = mask;
  return energy;
}

// P += sum over the rows u in [begin, end) of row_u[j] row_u[i] for the Jacobian columns
// j = 3 + c k + a (coordinate c, weight a < k) and the entries i the Gauss-Newton system reads:
// i = c and i in [3 + c k, 3 + (c + 1) k) (the other entries of P are left alone). Four rows at a
// time, so that each row of P is loaded and stored once per four. forward: rows of `stride`
// doubles; P: 3 k rows of stride.
MESHIK_SIMD_CLONES
void add_outer_products(const double* forward, int begin, int end, int k, int stride, double* __restrict outer) {
  constexpr int kRows = 4;
  int u = begin;
  for (; u + kRows <= end; u += kRows) {
    const double* __restrict r0 = forward + static_cast<size_t>(u) * stride;
    const double* __restrict r1 = r0 + stride;
    const double* __restrict r2 = r1 + stride;
    const double* __restrict r3 = r2 + stride;
    for (int c = 0; c < 3; ++c)
      for (int j = 3 + c * k; j < 3 + (c + 1) * k; ++j) {
        double* __restrict p = outer + (j - 3) * stride;
        p[c] += r0[j] * r0[c] + r1[j] * r1[c] + r2[j] * r2[c] + r3[j] * r3[c];
        for (int i = 3 + c * k; i < 3 + (c + 1) * k; ++i)
          p[i] += r0[j] * r0[i] + r1[j] * r1[i] + r2[j] * r2[i] + r3[j] * r3[i];
      }
  }
  for (; u < end; ++u) {
    const double* __restrict r = forward + static_cast<size_t>(u) * stride;
    for (int c = 0; c < 3; ++c)
      for (int j = 3 + c * k; j < 3 + (c + 1) * k; ++j) {
        outer[(j - 3) * stride + c] += r[j] * r[c];
        for (int i = 3 + c * k; i < 3 + (c + 1) * k; ++i) outer[(j - 3) * stride + i] += r[j] * r[i];
      }
  }
}

// The row width of rhs for `nrhs` columns: whole blocks of kLanes (8) columns, as scatter_batch
// needs, and a stride the solves accept (padded_width of a multiple of 8 is that multiple).
int row_width(int nrhs) { return PoseSystem::padded_width((nrhs + L - 1) / L * L); }

// For each of the `stride` columns of a row of rhs (PoseEvaluator::rhs_ with or without the
// Jacobian, #E = k): the row of blend_batch's output block that it takes (the first of the two
// columns of F or of dF/dw_a for coordinate c), or -1 for a padding column.
std::vector<int> column_sources(int k, bool with_jacobian, int stride) {
  std::vector<int> source(stride, -1);
  for (int c = 0; c < 3; ++c) {
    source[c] = 2 * c;
    for (int a = 0; with_jacobian && a < k; ++a) source[3 + c * k + a] = (a + 1) * 6 + 2 * c;
  }
  return source;
}

// The first 64-byte boundary in storage, after sizing storage to hold `count` doubles from there
// (new storage first written by `team` threads).
double* aligned_start(PageArray<double>& storage, size_t count, int team) {
  constexpr size_t kLineDoubles = 64 / sizeof(double);
  size_work_by_team(storage, count + kLineDoubles, team);
  const size_t misalignment = reinterpret_cast<uintptr_t>(storage.data()) / sizeof(double) % kLineDoubles;
  return storage.data() + (kLineDoubles - misalignment) % kLineDoubles;
}

}  // namespace

PoseEvaluator::PoseEvaluator(const ExampleSet::Impl& set, const PoseSystem& system,
                             FeatureSpace space, double regularization, const double* targets,
                             EvaluationBuffers& buffers, int team, Blend blend, const BlendRegions* regions,
                             const ExampleFeatures* features)
    : set_(set),
      system_(system),
      partition_(system.partition()),
      space_(space),
      blend_(blend),
      regions_(regions),
      features_(features != nullptr ? *features : set.features),
      num_examples_(features_.num_examples),
      num_weights_(regions != nullptr ? regions->num_regions * num_examples_ : num_examples_),
      regularization_(regularization),
      targets_(targets),
      team_(team),
      handle_offset_(6 * system.handle_triangles().size(), 0.0),
      batch_has_handle_(features_.num_batches, 0),
      batch_out_(static_cast<size_t>(partition_.num_chunks()) * blend_batch_size(num_examples_)),
      residual_(buffers.residual),
      jtj_lanes_(static_cast<size_t>(system.partition().num_chunks()) * num_weights_ * num_weights_ * L),
      jts_lanes_(static_cast<size_t>(system.partition().num_chunks()) * num_weights_ * L),
      handle_jts_(static_cast<size_t>(system.partition().num_chunks()) * num_weights_),
      curvature_size_((regions != nullptr ? regions->num_regions : 1) * num_examples_ * num_examples_ * L),
      curvature_lanes_(static_cast<size_t>(system.partition().num_chunks()) * curvature_size_),
      curvature_scratch_(static_cast<size_t>(system.partition().num_chunks()) * curvature_scratch_size(num_examples_)),
      chunk_energy_(system.partition().num_chunks()),
      chunk_inverted_(system.partition().num_chunks()),
      outer_products_(static_cast<size_t>(system.partition().num_chunks()) *
                      (regions != nullptr && regions->num_regions > 1
                           ? num_weights_ * (num_weights_ + 1)
                           : 3 * num_weights_ * row_width(3 * (num_weights_ + 1)))) {
  const int k = num_weights_;
  const size_t chunks = partition_.num_chunks();
  all_columns_.resize(k);
  for (int a = 0; a < k; ++a) all_columns_[a] = a;
  if (regions_ != nullptr) {
    region_out_.resize(chunks * 6 * (k + 1) * L);
    region_columns_.resize(chunks * k);
    region_source_.resize(chunks * row_width(3 * (k + 1)));
    region_lane_weights_.resize(chunks * num_examples_ * kCurvatureBatches * L);
    region_curvature_.resize(chunks * k * k);
    region_active_.resize(chunks * regions_->num_regions);
    chunk_regions_.resize(chunks);
    for (size_t chunk = 0; chunk < chunks; ++chunk) {
      std::vector<int>& present = chunk_regions_[chunk];
      for (int batch = partition_.batch_start[chunk]; batch < partition_.batch_start[chunk + 1]; ++batch)
        present.insert(present.end(), regions_->batch_regions(batch),
                       regions_->batch_regions(batch) + regions_->batch_region_count(batch));
      std::sort(present.begin(), present.end());
      present.erase(std::unique(present.begin(), present.end()), present.end());
    }
  }
  rhs_ = aligned_start(buffers.rhs, static_cast<size_t>(system.num_rows() + system.partition().num_extra_rows()) *
                                        row_width(3 * (k + 1)), team);
  size_work_by_team(residual_, 6 * L * static_cast<size_t>(features_.num_batches), team);
  // Handles' part of Q_j = sum over handle corners of target (x) g_q.
  const std::vector<int>& handle_of_vertex = system.handle_of_vertex();
  for (size_t slot = 0; slot < system.handle_triangles().size(); ++slot) {
    const int j = system.handle_triangles()[slot];
    batch_has_handle_[j / L] = 1;
    const int* t = set.triangles.data() + 3 * j;
    double g[6];
    corner_gradients(set.frames.gradient.data() + kGradientEntries * static_cast<size_t>(j), g);
    double* offset = handle_offset_.data() + 6 * slot;
    for (int q = 0; q < 3; ++q) {
      const int h = handle_of_vertex[t[q]];
      if (h < 0) continue;
      for (int c = 0; c < 3; ++c) {
        offset[2 * c] += targets[3 * h + c] * g[2 * q];
        offset[2 * c + 1] += targets[3 * h + c] * g[2 * q + 1];
      }
    }
  }
}

void PoseEvaluator::lane_weights(const double* weights, int first, int lanes, int row, double* out) const {
  const int e = num_examples_, count = regions_->num_regions;
  std::fill(out, out + static_cast<size_t>(e) * row, 0.0);
  for (int l = 0; l < lanes; ++l) {
    const double* share = regions_->share.data() + static_cast<size_t>(first + l) * count;
    for (int r = 0; r < count; ++r) {
      if (share[r] == 0.0) continue;
      for (int i = 0; i < e; ++i) out[i * row + l] += share[r] * weights[r * e + i];
    }
  }
}

int PoseEvaluator::blend_region_batch(const double* weights, bool with_jacobian, int batch, int chunk,
                                      double* region_out, int* columns, int* source) {
  const int e = num_examples_, k = num_weights_, count = regions_->num_regions;
  const int first = batch * L, lanes = std::min(L, set_.num_triangles - first);
  double* out = batch_out_.data() + static_cast<size_t>(chunk) * blend_batch_size(e);
  const int whole = regions_->whole_region[batch];
  if (whole >= 0) {
    blend_batch(features_, space_, weights + whole * e, batch, out, blend_);
  } else {
    double* lane_weight = region_lane_weights_.data() + static_cast<size_t>(chunk) * e * kCurvatureBatches * L;
    lane_weights(weights, first, lanes, L, lane_weight);
    blend_batch_lanes(features_, space_, blend_, lane_weight, batch, out);
  }
  std::copy(out, out + 6 * L, region_out);
  int n = 0;
  for (int t = 0; with_jacobian && t < regions_->batch_region_count(batch); ++t) {
    const int r = regions_->batch_regions(batch)[t];
    double share[L] = {};
    for (int l = 0; l < lanes; ++l) share[l] = regions_->share[static_cast<size_t>(first + l) * count + r];
    for (int i = 0; i < e; ++i, ++n) {
      columns[n] = r * e + i;
      const double* from = out + (i + 1) * 6 * L;
      double* to = region_out + (n + 1) * 6 * L;
      if (whole >= 0) {
        std::copy(from, from + 6 * L, to);  // shares of one: the blend's own bits
      } else {
        for (int row = 0; row < 6; ++row)
          for (int l = 0; l < L; ++l) to[row * L + l] = share[l] * from[row * L + l];
      }
    }
  }
  std::fill(source, source + stride_, -1);
  for (int c = 0; c < 3; ++c) {
    source[c] = 2 * c;
    for (int a = 0; a < n; ++a) source[3 + c * k + columns[a]] = (a + 1) * 6 + 2 * c;
  }
  return n;
}

void PoseEvaluator::assemble_chunk(const double* weights, bool with_jacobian, const int* source, int chunk) {
  const int e = num_examples_;
  const int k = num_weights_;
  const int m = set_.num_triangles;
  const std::vector<int>& slot_of_triangle = system_.handle_triangle_slot();
  const int* corner_row = partition_.corner_row.data();
  double* out = batch_out_.data() + static_cast<size_t>(chunk) * blend_batch_size(e);
  double* jtj_lanes = jtj_lanes_.data() + static_cast<size_t>(chunk) * k * k * L;
  double* jts_lanes = jts_lanes_.data() + static_cast<size_t>(chunk) * k * L;
  double* handle_jts = handle_jts_.data() + static_cast<size_t>(chunk) * k;
  double* region_out = regions_ ? region_out_.data() + static_cast<size_t>(chunk) * 6 * (k + 1) * L : nullptr;
  int* columns = regions_ ? region_columns_.data() + static_cast<size_t>(chunk) * k : nullptr;
  int* batch_source = regions_ ? region_source_.data() + static_cast<size_t>(chunk) * row_width(3 * (k + 1)) : nullptr;
  const int end = partition_.batch_start[chunk + 1];
  if (several_regions())  // only the blocks of the regions this chunk's batches carry
    for_chunk_region_blocks(chunk, [&](int a, int b) {
      std::fill(jtj_lanes + (static_cast<size_t>(a) * k + b) * L, jtj_lanes + (static_cast<size_t>(a) * k + b + 1) * L, 0.0);
    });
  for (int batch = partition_.batch_start[chunk]; batch < end; ++batch) {
    if (batch + 1 < end) prefetch_rows(rhs_, stride_, corner_row + 3 * static_cast<size_t>(batch + 1) * L, 3 * L);
    const double* block = out;  // F_j, then the Jacobian's columns of the batch
    const int* block_source = source;
    int block_columns = k;
    if (regions_ != nullptr) {
      block_columns = blend_region_batch(weights, with_jacobian, batch, chunk, region_out, columns, batch_source);
      block = region_out;
      block_source = batch_source;
    } else {
      blend_batch(features_, space_, weights, batch, out, blend_);
    }
    std::copy(block, block + 6 * L, residual_.data() + static_cast<size_t>(batch) * 6 * L);
    const int first = batch * L;
    const int lanes = std::min(L, m - first);
    if (with_jacobian) {
      accumulate_mapped_products(block, block_columns, regions_ != nullptr ? columns : all_columns_.data(), k,
                                 jtj_lanes, jts_lanes);
      // J^T s = J^T F - J^T (handles' part of Q) on the few triangles touching a handle.
      for (int l = 0; batch_has_handle_[batch] && l < lanes; ++l) {
        const int slot = slot_of_triangle[first + l];
        if (slot < 0) continue;
        for (int a = 0; a < block_columns; ++a) {
          const int column = regions_ != nullptr ? columns[a] : a;
          for (int q = 0; q < 6; ++q)
            handle_jts[column] -= block[((a + 1) * 6 + q) * L + l] * handle_offset_[6 * static_cast<size_t>(slot) + q];
        }
      }
    }
    scatter_batch(block, block_source, stride_, lanes, corner_row + 3 * static_cast<size_t>(first),
                  set_.frames.gradient.data() + kGradientEntries * static_cast<size_t>(first), rhs_);
  }
}

void PoseEvaluator::assemble(const double* weights, bool with_jacobian) {
  const int k = num_weights_;
  const int rows = system_.num_rows();
  const int all_rows = rows + partition_.num_extra_rows();
  const int chunks = partition_.num_chunks();
  if (!several_regions()) std::fill(jtj_lanes_.begin(), jtj_lanes_.end(), 0.0);
  std::fill(jts_lanes_.begin(), jts_lanes_.end(), 0.0);
  std::fill(handle_jts_.begin(), handle_jts_.end(), 0.0);
  const std::vector<int> source = regions_ != nullptr ? std::vector<int>() : column_sources(k, with_jacobian, stride_);
#pragma omp parallel num_threads(team_)
  {
    // Every system row starts as -K_fh x_h in its first 3 columns (nonzero only in the rows
    // coupled to a handle: the sparse K_fh is applied, no dense copy of its product is kept) and
    // zero in the others; the extra rows start at zero.
#pragma omp for schedule(dynamic, kRowsPerTask)
    for (int u = 0; u < all_rows; ++u) {
      double* row = rhs_ + static_cast<size_t>(u) * stride_;
      std::fill(row, row + stride_, 0.0);
    }
#pragma omp single
    system_.subtract_handle_coupling(targets_, rhs_, stride_);
#pragma omp for schedule(dynamic, 1)
    for (int chunk = 0; chunk < chunks; ++chunk) assemble_chunk(weights, with_jacobian, source.data(), chunk);
  }
  // The chunks' shares of their shared rows and their sums, in chunk order.
  for (int e = 0; e < partition_.num_extra_rows(); ++e) {
    double* row = rhs_ + static_cast<size_t>(partition_.extra_target[e]) * stride_;
    const double* extra = rhs_ + static_cast<size_t>(rows + e) * stride_;
    for (int i = 0; i < stride_; ++i) row[i] += extra[i];
  }
  sum_chunks(jts_lanes_, k * L);
  sum_chunks(handle_jts_, k);
  jts_ = Eigen::Map<const Eigen::VectorXd>(handle_jts_.data(), k);
  for (int a = 0; a < k; ++a)
    for (int l = 0; l < L; ++l) jts_(a) += jts_lanes_[a * L + l];
  if (several_regions()) {
    sum_region_blocks();
    return;
  }
  sum_chunks(jtj_lanes_, k * k * L);
  jtj_.resize(k, k);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b <= a; ++b) {
      double sum = 0.0;
      for (int l = 0; l < L; ++l) sum += jtj_lanes_[(a * k + b) * L + l];
      jtj_(a, b) = jtj_(b, a) = sum;
    }
  }
}

void PoseEvaluator::for_chunk_region_blocks(int chunk, const std::function<void(int, int)>& visit) const {
  const int e = num_examples_;
  const std::vector<int>& present = chunk_regions_[chunk];
  for (size_t t = 0; t < present.size(); ++t)
    for (size_t q = 0; q <= t; ++q)
      for (int a = present[t] * e; a < (present[t] + 1) * e; ++a)
        for (int b = present[q] * e; b < (present[q] + 1) * e && b <= a; ++b) visit(a, b);
}

void PoseEvaluator::sum_region_blocks() {
  const int k = num_weights_;
  jtj_.setZero(k, k);
  for (int chunk = 0; chunk < partition_.num_chunks(); ++chunk) {
    const double* lanes = jtj_lanes_.data() + static_cast<size_t>(chunk) * k * k * L;
    for_chunk_region_blocks(chunk, [&](int a, int b) {
      double sum = 0.0;
      for (int l = 0; l < L; ++l) sum += lanes[(static_cast<size_t>(a) * k + b) * L + l];
      jtj_(a, b) += sum;
    });
  }
  jtj_.triangularView<Eigen::StrictlyUpper>() = jtj_.transpose();
}

void PoseEvaluator::sum_chunks(std::vector<double>& per_chunk, int size) const {
  for (int chunk = 1; chunk < partition_.num_chunks(); ++chunk)
    for (int i = 0; i < size; ++i) per_chunk[i] += per_chunk[static_cast<size_t>(chunk) * size + i];
}

void PoseEvaluator::gather_vertices(double* vertices) const {
  const std::vector<int>& unknown_of_vertex = system_.unknown_of_vertex();
  const std::vector<int>& handle_of_vertex = system_.handle_of_vertex();
#pragma omp for schedule(dynamic, kRowsPerTask)
  for (int v = 0; v < set_.num_vertices; ++v) {
    const double* from = set_.rest.data() + 3 * static_cast<size_t>(v);
    if (unknown_of_vertex[v] >= 0) {
      from = rhs_ + static_cast<size_t>(unknown_of_vertex[v]) * stride_;
    } else if (handle_of_vertex[v] >= 0) {
      from = targets_ + 3 * static_cast<size_t>(handle_of_vertex[v]);
    }
    double* to = vertices + 3 * static_cast<size_t>(v);
    to[0] = from[0];  // three assignments, not a library call per vertex
    to[1] = from[1];
    to[2] = from[2];
  }
}

void PoseEvaluator::residual_chunk(const double* vertices, int chunk) {
  double energy = 0.0;
  std::vector<int>& inverted = chunk_inverted_[chunk];
  inverted.clear();
  for (int batch = partition_.batch_start[chunk]; batch < partition_.batch_start[chunk + 1]; ++batch) {
    const int first = batch * L;
    unsigned mask = 0;
    energy += batch_residual(vertices, set_.triangles.data() + 3 * static_cast<size_t>(first),
                             set_.frames.gradient.data() + kGradientEntries * static_cast<size_t>(first),
                             std::min(L, set_.num_triangles - first),
                             residual_.data() + static_cast<size_t>(batch) * 6 * L, &mask);
    for (int l = 0; mask != 0; ++l, mask >>= 1)
      if (mask & 1u) inverted.push_back(first + l);
  }
  chunk_energy_[chunk] = energy;
}

double PoseEvaluator::pose_and_residual(double* vertices, std::vector<int>& inverted) {
  const int chunks = partition_.num_chunks();
#pragma omp parallel num_threads(team_)
  {
    gather_vertices(vertices);  // a work-shared loop: its barrier precedes the residuals
#pragma omp for schedule(dynamic, 1)
    for (int chunk = 0; chunk < chunks; ++chunk) residual_chunk(vertices, chunk);
  }
  double energy = 0.0;
  inverted.clear();
  for (int chunk = 0; chunk < chunks; ++chunk) {
    energy += chunk_energy_[chunk];
    inverted.insert(inverted.end(), chunk_inverted_[chunk].begin(), chunk_inverted_[chunk].end());
  }
  return energy;
}

void PoseEvaluator::add_region_curvature(const double* weights, int chunk) {
  const int e = num_examples_, k = num_weights_, count = regions_->num_regions;
  constexpr int N = kCurvatureBatches * L;
  float* scratch = curvature_scratch_.data() + static_cast<size_t>(chunk) * curvature_scratch_size(e);
  double* lanes = curvature_lanes_.data() + static_cast<size_t>(chunk) * curvature_size_;
  double* dense = region_curvature_.data() + static_cast<size_t>(chunk) * k * k;
  double* lane_weight = region_lane_weights_.data() + static_cast<size_t>(chunk) * e * N;
  const int batches = features_.num_batches;
  for (int batch = partition_.batch_start[chunk]; batch < partition_.batch_start[chunk + 1];
       batch += kCurvatureBatches) {
    const double* residual = residual_.data() + static_cast<size_t>(batch) * 6 * L;
    const int whole = regions_->whole_region[batch];
    if (whole >= 0 && (batch + 1 >= batches || regions_->whole_region[batch + 1] == whole)) {
      // Inside one region: as without regions, into that region's block (#E by #E by kLanes).
      add_residual_curvature(features_, weights + whole * e, batch, residual, scratch,
                             lanes + static_cast<size_t>(whole) * e * e * L, blend_);
      continue;
    }
    const int first = batch * L, pair_lanes = std::min(N, set_.num_triangles - first);
    lane_weights(weights, first, pair_lanes, N, lane_weight);
    const float* curvature = residual_curvature_lanes(features_, blend_, lane_weight, batch, residual, scratch);
    // d2F_j/dW_ra dW_sb = alpha_jr alpha_js d2F_j/dw_a dw_b.
    for (int l = 0; l < pair_lanes; ++l) {
      const double* share = regions_->share.data() + static_cast<size_t>(first + l) * count;
      for (int r = 0; r < count; ++r) {
        if (share[r] == 0.0) continue;
        for (int s = 0; s < count; ++s) {
          if (share[s] == 0.0) continue;
          const double product = share[r] * share[s];
          for (int a = 0; a < e; ++a)
            for (int b = 0; b < e; ++b) {
              const int pair = a >= b ? a * e + b : b * e + a;
              dense[static_cast<size_t>(r * e + a) * k + s * e + b] += product * curvature[pair * N + l];
            }
        }
      }
    }
  }
}

void PoseEvaluator::add_second_order(PoseEvaluation& at) {
  if (at.evaluation == 0 || at.evaluation != evaluations_)
    throw std::logic_error("PoseEvaluator::add_second_order: not the evaluator's last evaluation");
  const int k = num_weights_;
  const int e = num_examples_;
  at.second_order.setZero(k, k);
  at.has_second_order = true;
  if (space_ == FeatureSpace::kLinear) return;
  std::fill(curvature_lanes_.begin(), curvature_lanes_.end(), 0.0);
  std::fill(region_curvature_.begin(), region_curvature_.end(), 0.0);
  const int chunks = partition_.num_chunks();
  const double* weights = at.weights.data();
#pragma omp parallel for schedule(dynamic, 1) num_threads(team_)
  for (int chunk = 0; chunk < chunks; ++chunk) {
    if (regions_ != nullptr) {
      add_region_curvature(weights, chunk);
      continue;
    }
    float* scratch = curvature_scratch_.data() + static_cast<size_t>(chunk) * curvature_scratch_size(k);
    double* lanes = curvature_lanes_.data() + static_cast<size_t>(chunk) * curvature_size_;
    for (int batch = partition_.batch_start[chunk]; batch < partition_.batch_start[chunk + 1];
         batch += kCurvatureBatches)
      add_residual_curvature(features_, weights, batch, residual_.data() + static_cast<size_t>(batch) * 6 * L,
                             scratch, lanes, blend_);
  }
  sum_chunks(curvature_lanes_, curvature_size_);
  // Without regions one block of #E = K; with them one per region, at region r's offset r #E #E L.
  const int blocks = regions_ != nullptr ? regions_->num_regions : 1;
  for (int r = 0; r < blocks; ++r) {
    const double* lanes = curvature_lanes_.data() + static_cast<size_t>(r) * e * e * L;
    for (int a = 0; a < e; ++a)
      for (int b = 0; b <= a; ++b) {
        double sum = 0.0;
        for (int l = 0; l < L; ++l) sum += lanes[(a * e + b) * L + l];
        at.second_order(r * e + a, r * e + b) = at.second_order(r * e + b, r * e + a) = -sum;
      }
  }
  if (regions_ == nullptr || regions_->num_regions == 1) return;
  sum_chunks(region_curvature_, k * k);
  at.second_order -= Eigen::Map<const Eigen::MatrixXd>(region_curvature_.data(), k, k);
}

double PoseEvaluator::region_smoothness_energy(const double* weights, Eigen::VectorXd* product) const {
  const int k = num_weights_, e = num_examples_;
  if (product != nullptr) product->setZero(k);
  if (regions_ == nullptr || regions_->num_regions == 1) return 0.0;
  const Eigen::Map<const Eigen::MatrixXd> w(weights, e, regions_->num_regions);  // column r: W_r
  const Eigen::MatrixXd mw = w * regions_->smoothness;  // column r: sum_s M_rs W_s
  if (product != nullptr) *product = Eigen::Map<const Eigen::VectorXd>(mw.data(), k);
  return w.cwiseProduct(mw).sum();
}

void PoseEvaluator::global_products(Eigen::MatrixXd& hth, Eigen::VectorXd& htx) {
  const int k = num_weights_;
  std::fill(outer_products_.begin(), outer_products_.end(), 0.0);
  const int chunks = partition_.num_chunks();
  const int outer_size = 3 * k * stride_;
#pragma omp parallel for schedule(dynamic, 1) num_threads(team_)
  for (int chunk = 0; chunk < chunks; ++chunk)
    add_outer_products(rhs_, partition_.row_start[chunk], partition_.row_start[chunk + 1], k, stride_,
                       outer_products_.data() + static_cast<size_t>(chunk) * outer_size);
  sum_chunks(outer_products_, outer_size);
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < k; ++a) {
      const double* p = outer_products_.data() + static_cast<size_t>(c * k + a) * stride_;
      htx(a) += p[c];
      for (int b = 0; b < k; ++b) hth(a, b) += p[3 + c * k + b];
    }
}

void PoseEvaluator::region_products(Eigen::MatrixXd& hth, Eigen::VectorXd& htx) {
  const int k = num_weights_, e = num_examples_, count = regions_->num_regions;
  std::fill(outer_products_.begin(), outer_products_.end(), 0.0);
  const int chunks = partition_.num_chunks();
  const int outer_size = k * (k + 1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(team_)
  for (int chunk = 0; chunk < chunks; ++chunk)
    add_region_outer_products(rhs_, partition_.row_start[chunk], partition_.row_start[chunk + 1], count, e, stride_,
                              region_active_.data() + static_cast<size_t>(chunk) * count,
                              outer_products_.data() + static_cast<size_t>(chunk) * outer_size);
  sum_chunks(outer_products_, outer_size);
  for (int a = 0; a < k; ++a) {
    htx(a) = outer_products_[static_cast<size_t>(a) * (k + 1)];
    for (int b = 0; b < k; ++b) hth(a, b) = region_outer_product(outer_products_.data(), count, e, a, b);
  }
}

void PoseEvaluator::assemble_and_forward_solve(const double* weights, bool with_jacobian, PoseEvaluation& out) {
  stride_ = row_width(with_jacobian ? 3 * (num_weights_ + 1) : 3);
  assemble(weights, with_jacobian);
  forward_solve_assembled(weights, with_jacobian, out);
}

void PoseEvaluator::forward_solve_assembled(const double* weights, bool with_jacobian, PoseEvaluation& out) {
  const int k = num_weights_;
  const int nrhs = with_jacobian ? 3 * (k + 1) : 3;
  system_.forward_solve(rhs_, stride_, nrhs, team_);
  out.weights.assign(weights, weights + k);
  if (!with_jacobian) return;
  // H^T K'^{-1} H and H^T x0 as (L^{-1} H)^T (L^{-1} H) and (L^{-1} H)^T (L^{-1} b): entries of
  // the outer products of the forward-solved rows, summed over the coordinates.
  Eigen::MatrixXd hth = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd htx = Eigen::VectorXd::Zero(k);
  if (regions_ != nullptr && regions_->num_regions > 1)
    region_products(hth, htx);
  else
    global_products(hth, htx);
  const Eigen::Map<const Eigen::VectorXd> w(weights, k);
  out.schur = jtj_ - 0.5 * (hth + hth.transpose());
  out.schur.diagonal().array() += regularization_;
  out.step_rhs = htx - jts_ - regularization_ * w;
  if (regions_ == nullptr || regions_->num_regions == 1) return;
  // + W^T (M kron I) W: half its Hessian is M kron I, half its gradient (M kron I) W.
  Eigen::VectorXd smooth_gradient;
  region_smoothness_energy(weights, &smooth_gradient);
  const int e = num_examples_;
  for (int r = 0; r < regions_->num_regions; ++r)
    for (int s = 0; s < regions_->num_regions; ++s)
      out.schur.block(r * e, s * e, e, e).diagonal().array() += regions_->smoothness(r, s);
  out.step_rhs -= smooth_gradient;
}

void PoseEvaluator::evaluate(const double* weights, bool with_jacobian, PoseEvaluation& out) {
  assemble_and_forward_solve(weights, with_jacobian, out);
  system_.backward_solve(rhs_, stride_, 3, team_);
  out.vertices.resize(3 * static_cast<size_t>(set_.num_vertices));
  const Eigen::Map<const Eigen::VectorXd> w(weights, num_weights_);
  out.energy =
      pose_and_residual(out.vertices.data(), out.inverted_triangles) + regularization_ * w.squaredNorm();
  out.energy += system_.soft_handle_energy(out.vertices.data(), targets_);
  if (regions_ != nullptr && regions_->num_regions > 1) out.energy += region_smoothness_energy(weights, nullptr);
  out.has_second_order = false;
  out.evaluation = ++evaluations_;
}

void PoseEvaluator::solve_jacobian_rows(const std::vector<int>& rows) {
  system_.backward_solve_rows(rhs_, stride_, 3 * (num_weights_ + 1), rows, team_);
}

void PoseEvaluator::assemble_system(const double* weights) {
  stride_ = row_width(3 * (num_weights_ + 1));
  assemble(weights, true);
}

void PoseEvaluator::solve_assembled_system(const double* weights, PoseEvaluation& out) {
  forward_solve_assembled(weights, true, out);
  out.vertices.clear();
  out.inverted_triangles.clear();
  out.energy = 0.0;
  out.has_second_order = false;
  out.evaluation = 0;  // no pose: add_second_order refuses it
}

}  // namespace meshik
