// Precomputation of the examples' per-triangle features (polar decomposition, rotation logs with
// consistent branches, stretches projected on the rest planes) and their batched blend.
#include "feature_space.h"

#include <algorithm>

#include <string>
#include <type_traits>
#include <utility>

#include "lane_math.h"
#include "page_arrays.h"
#include "polar_batch.h"
#include "rotation_branches.h"
#include "simd_clones.h"
#include "so3.h"
#include "thread_count.h"

namespace meshik {

static_assert(kPolarLanes == kLanes && kGradientLanes == kLanes, "one polar batch per feature batch");

namespace {

// Copies `rows` rows of kLanes values (double: rounded, or float) from each of two batches (second
// may be null: zeros) into rows of 2 kLanes floats, the first batch's lanes first: one pair of
// kCurvatureBatches.
template <typename Value>
MESHIK_LANE_INLINE void float_pair(const Value* first, const Value* second, int rows, float* out) {
  for (int row = 0; row < rows; ++row) {
    for (int l = 0; l < kLanes; ++l) out[row * 2 * kLanes + l] = static_cast<float>(first[row * kLanes + l]);
    for (int l = 0; l < kLanes; ++l)
      out[row * 2 * kLanes + kLanes + l] = second != nullptr ? static_cast<float>(second[row * kLanes + l]) : 0.0f;
  }
}
static_assert(kCurvatureBatches == 2, "float_pair packs two batches");

// Writes the per-example blocks of features (sized, plane basis set): the stretches and rotation
// logs (consistent branches, or principal ones) of the nonlinear space and the linear space's
// gradients, for every example, on `team` threads, as Stored values (features' precision). Its
// working arrays (rotations, logs and edge distances of a group of examples) are freed on return.
template <typename Stored>
void fill_example_blocks(const TriangleFrames& frames, const TriangleAdjacency& adjacency, const int* triangles,
                         const std::vector<const double*>& examples, const ProgressCallback& progress,
                         bool consistent_branches, int team, const std::function<int()>& threads_free,
                         ExampleFeatures& features) {
  const int m = features.num_triangles;
  const int k = features.num_examples;
  FeatureValues<Stored>& values = values_of<Stored>(features);
  // Examples go in groups of `team`: the features of each (all threads over its triangles), then
  // the groups' branch choices side by side (one thread each: a spanning tree grows serially). A
  // smaller group, when #E is not a multiple of the team, goes first: its branch choices leave
  // threads idle, and early on the ExampleSet's analysis thread is there to take their cores.
  const int group_size = std::max(1, std::min(team, k));
  PageArray<Eigen::Matrix3d> rotations;
  assign_by_team(rotations, m, Eigen::Matrix3d(Eigen::Matrix3d::Zero()), team);
  // The group's principal logs, member g's from entry g m on (one array, its pages kept for the
  // Solver's arrays like the distances'). Each log is written before it is read, and Eigen's
  // vectors are not initialized: the pages are first touched by the team's writes below.
  PageArray<Eigen::Vector3d> logs;
  size_unwritten(logs, static_cast<size_t>(m) * group_size);
  // The group's edge distances, member g's from entry g #adjacency on (one array, its pages kept for
  // the Solver's arrays once the features are done: page_pool.h).
  const size_t edges = adjacency.neighbour.size();
  PageArray<double> distances;
  assign_by_team(distances, edges * group_size, 0.0, team);
  const TriangleComponents components = consistent_branches ? triangle_components(adjacency) : TriangleComponents();
  const int batches_per_task = dynamic_chunk(features.num_batches, team);
  // The threads of the team a pass starting now may use.
  const auto threads_now = [&threads_free, team] { return threads_free ? threads_free() : team; };
  for (int group = 0, members = k % group_size == 0 ? group_size : k % group_size; group < k;
       group += members, members = group_size) {
    for (int g = 0; g < members; ++g) {
      const int i = group + g;
      // Triangles are independent: each batch of kLanes triangles is one task (one thread writes
      // every lane of a block), so the features are the same bits for any number of threads. The
      // batches are handed out in chunks as threads come free: the ExampleSet's analysis thread
      // shares the cores, and equal static shares would leave a core idle while the thread that
      // shares its core with it finishes.
#pragma omp parallel num_threads(threads_now())
      {
#pragma omp for schedule(dynamic, batches_per_task)
        for (int batch = 0; batch < features.num_batches; ++batch) {
          const int first = batch * kLanes, count = std::min(m - first, kLanes);
          double rotation[9][kLanes], plane_stretch[6][kLanes], log[3][kLanes];
          triangle_polar_and_log_batch(frames, features.plane_basis.data(), triangles, examples[i], first, count,
                                       rotation, plane_stretch, log);
          const size_t block = static_cast<size_t>(batch) * k + i;
          // (S - I) U, zero in the padding lanes.
          Stored* stretch_block = values.nonlinear.data() + 9 * kLanes * block + 3 * kLanes;
          for (int r = 0; r < 6; ++r)
            for (int l = 0; l < kLanes; ++l)
              stretch_block[r * kLanes + l] = l < count ? static_cast<Stored>(plane_stretch[r][l]) : Stored(0);
          for (int r = 0; r < 3; ++r)
            for (int l = 0; l < count; ++l)
              values.nonlinear[9 * kLanes * block + r * kLanes + l] = static_cast<Stored>(log[r][l]);
          for (int l = 0; l < count; ++l) {
            for (int e = 0; e < 9; ++e) rotations[first + l](e / 3, e % 3) = rotation[e][l];
            logs[static_cast<size_t>(m) * g + first + l] = Eigen::Vector3d(log[0][l], log[1][l], log[2][l]);
          }
        }
        if (consistent_branches) {
#pragma omp for schedule(dynamic, batches_per_task)
          for (int batch = 0; batch < features.num_batches; ++batch)
            rotation_edge_distances(adjacency, rotations.data(), batch * kLanes, std::min(m, (batch + 1) * kLanes),
                                    distances.data() + edges * g);
        }
      }
    }
#pragma omp parallel for schedule(static, 1) num_threads(std::min(threads_now(), members))
    for (int g = 0; g < members; ++g) {
      if (!consistent_branches) continue;
      // The principal logs are in place: write those given another branch.
      const int i = group + g;
      Eigen::Vector3d* member_logs = logs.data() + static_cast<size_t>(m) * g;
      for (int j : choose_consistent_log_branches(adjacency, components, distances.data() + edges * g, member_logs)) {
        Stored* block = values.nonlinear.data() + 9 * kLanes * (static_cast<size_t>(j / kLanes) * k + i);
        for (int r = 0; r < 3; ++r) block[r * kLanes + j % kLanes] = static_cast<Stored>(member_logs[j](r));
      }
    }
    for (int i = group; i < group + members; ++i)
      if (progress && !progress(static_cast<double>(i + 1) / k, "example features"))
        throw Cancelled("cancelled while computing the features of example " + std::to_string(i));
  }
}

}  // namespace

ExampleFeatures compute_example_features(TriangleFrames& frames,
                                         const TriangleAdjacency& adjacency, const int* triangles,
                                         const std::vector<const double*>& examples,
                                         const ProgressCallback& progress,
                                         bool consistent_branches, int threads, FeaturePrecision precision,
                                         const std::function<int()>& threads_free) {
  const int m = frames.num_triangles;
  const int k = static_cast<int>(examples.size());
  ExampleFeatures features;
  features.num_examples = k;
  features.num_triangles = m;
  features.num_batches = (m + kLanes - 1) / kLanes;
  features.precision = precision;
  const size_t slots = static_cast<size_t>(features.num_batches) * kLanes;
  const int team = thread_count(threads);
  visit_feature_values(features, [&](auto& values) {
    using Stored = typename std::decay_t<decltype(values)>::Value;
    assign_by_team(values.nonlinear, 9 * slots * k, Stored(0), team);
  });
  features.plane_basis = std::move(frames.plane_basis);  // the same layout (kGradientLanes == kLanes)

  if (precision == FeaturePrecision::kSingle)
    fill_example_blocks<float>(frames, adjacency, triangles, examples, progress, consistent_branches, team,
                               threads_free, features);
  else
    fill_example_blocks<double>(frames, adjacency, triangles, examples, progress, consistent_branches, team,
                                threads_free, features);
  return features;
}

namespace {

constexpr int L = kLanes;

// How many batches ahead the blend asks for features (best of 2, 4 and 8 on the elephant).
constexpr int kPrefetchDistance = 4;

// The helpers below work on N lanes of Real: N = kLanes doubles (one batch) for the blend, and
// 2 kLanes floats (two batches) for the curvature. Lane-minor blocks have rows of N values.

// The rotation of a nonlinear blend for N triangles: phi = sum_i w_i phi_i, its Rodrigues
// coefficients and R = exp(phi) (row-major), per lane.
template <typename Real, int N>
struct BatchRotation {
  Real phi[3][N];
  Real theta_squared[N];
  Real a[N], b[N], c[N];
  Real rot[9][N];
};

// Weights shared by every lane: example i's is w[i].
struct SharedWeights {
  const double* w;
  template <typename Real>
  MESHIK_LANE_INLINE Real at(int i, int /*lane*/) const { return static_cast<Real>(w[i]); }
};

// Weights per lane (spatially varying blends): example i's in lane l is w[i stride + l].
struct LaneWeights {
  const double* w;
  int stride;
  template <typename Real>
  MESHIK_LANE_INLINE Real at(int i, int lane) const { return static_cast<Real>(w[i * stride + lane]); }
};

// Writes s U to 6 rows of N lanes (start), per lane s = 1 (affine) or the weights' sum over the
// #E examples (free); basis U: 6 rows of N.
template <typename Real, int N, typename Weights>
MESHIK_LANE_INLINE void scaled_basis(const Weights& w, int k, Blend blend, const Real* basis, Real* start) {
  if (blend == Blend::kAffine) {
    for (int e = 0; e < 6 * N; ++e) start[e] = basis[e];
    return;
  }
  Real sum[N];
  for (int l = 0; l < N; ++l) sum[l] = 0;
  for (int i = 0; i < k; ++i)
    for (int l = 0; l < N; ++l) sum[l] += w.template at<Real>(i, l);
  for (int e = 0; e < 6 * N; ++e) start[e] = sum[e % N] * basis[e];
}

// R = I + a [phi]_x + b [phi]_x^2 (row-major) for one lane's phi = (x, y, z) and its Rodrigues
// coefficients a, b (rodrigues_lanes).
template <typename Real>
MESHIK_LANE_INLINE void rodrigues_rotation(Real x, Real y, Real z, Real a, Real b, Real (&rot)[9]) {
  const Real one = 1;
  rot[0] = one - b * (y * y + z * z);
  rot[1] = b * x * y - a * z;
  rot[2] = b * x * z + a * y;
  rot[3] = b * x * y + a * z;
  rot[4] = one - b * (x * x + z * z);
  rot[5] = b * y * z - a * x;
  rot[6] = b * x * z - a * y;
  rot[7] = b * y * z + a * x;
  rot[8] = one - b * (x * x + y * y);
}

// Fills r for the triangles whose features (#E blocks of 9 rows) start at feature; weights w
// (SharedWeights or LaneWeights over #E examples).
template <typename Real, int N, typename Weights>
MESHIK_LANE_INLINE void blend_rotation(const Real* feature, const Weights& w, int k, BatchRotation<Real, N>& r) {
  for (int d = 0; d < 3; ++d)
    for (int l = 0; l < N; ++l) r.phi[d][l] = 0;
  for (int i = 0; i < k; ++i) {
    for (int d = 0; d < 3; ++d)
      for (int l = 0; l < N; ++l) r.phi[d][l] += w.template at<Real>(i, l) * feature[(i * 9 + d) * N + l];
  }
  for (int l = 0; l < N; ++l)
    r.theta_squared[l] = r.phi[0][l] * r.phi[0][l] + r.phi[1][l] * r.phi[1][l] + r.phi[2][l] * r.phi[2][l];
  rodrigues_lanes<N>(r.theta_squared, r.a, r.b, r.c);
  for (int l = 0; l < N; ++l) {
    Real rot[9];
    rodrigues_rotation(r.phi[0][l], r.phi[1][l], r.phi[2][l], r.a[l], r.b[l], rot);
    for (int e = 0; e < 9; ++e) r.rot[e][l] = rot[e];
  }
}

// psi = J_l(phi) u per lane, u: 3 rows of lanes.
template <typename Real, int N>
MESHIK_LANE_INLINE void left_jacobian_times(const BatchRotation<Real, N>& r, const Real* u, Real psi[3][N]) {
  for (int l = 0; l < N; ++l) {
    const Real x = r.phi[0][l], y = r.phi[1][l], z = r.phi[2][l];
    const Real u0 = u[l], u1 = u[N + l], u2 = u[2 * N + l];
    const Real c0 = y * u2 - z * u1, c1 = z * u0 - x * u2, c2 = x * u1 - y * u0;
    psi[0][l] = u0 + r.b[l] * c0 + r.c[l] * (y * c2 - z * c1);
    psi[1][l] = u1 + r.b[l] * c1 + r.c[l] * (z * c0 - x * c2);
    psi[2][l] = u2 + r.b[l] * c2 + r.c[l] * (x * c1 - y * c0);
  }
}

// target = psi x m (column by column) + R d for 3 by 2 lane-minor blocks m, d (d may be null:
// no R d term).
template <typename Real, int N>
MESHIK_LANE_INLINE void cross_plus_rotated(const BatchRotation<Real, N>& r, const Real psi[3][N], const Real* m,
                                           const Real* d, Real* target) {
  for (int row = 0; row < 3; ++row) {
    const int p = (row + 1) % 3, q = (row + 2) % 3;
    for (int col = 0; col < 2; ++col) {
      const Real* mp = m + (2 * p + col) * N;
      const Real* mq = m + (2 * q + col) * N;
      Real* t = target + (2 * row + col) * N;
      for (int l = 0; l < N; ++l) t[l] = psi[p][l] * mq[l] - psi[q][l] * mp[l];
      if (d == nullptr) continue;
      for (int l = 0; l < N; ++l)
        t[l] += r.rot[3 * row][l] * d[col * N + l] + r.rot[3 * row + 1][l] * d[(2 + col) * N + l] +
                r.rot[3 * row + 2][l] * d[(4 + col) * N + l];
    }
  }
}

// x = sum over the two columns of m_col x res_col, per lane (3 rows of lanes); m, res: 3 by 2
// lane-minor blocks. Then <res, [v]_x m> = v . x.
template <typename Real, int N>
MESHIK_LANE_INLINE void column_cross_sum(const Real* m, const Real* res, Real x[3][N]) {
  for (int row = 0; row < 3; ++row) {
    const int p = (row + 1) % 3, q = (row + 2) % 3;
    for (int l = 0; l < N; ++l) {
      Real sum = 0;
      for (int col = 0; col < 2; ++col)
        sum += m[(2 * p + col) * N + l] * res[(2 * q + col) * N + l] -
               m[(2 * q + col) * N + l] * res[(2 * p + col) * N + l];
      x[row][l] = sum;
    }
  }
}

// Asks the L2 cache for `count` values from p (a later batch's features: the hardware prefetcher
// alone leaves the blend waiting on memory). Not into L1: there, a whole batch's lines at once
// fill the miss buffers and stall the blend (measured on the elephant).
template <typename Real>
MESHIK_LANE_INLINE void prefetch_values(const Real* p, size_t count) {
  constexpr size_t kLineValues = 64 / sizeof(Real);
  for (size_t e = 0; e < count; e += kLineValues) __builtin_prefetch(p + e, 0, 2);
}

template <typename Real, int N>
MESHIK_LANE_INLINE Real dot_lane(const Real u[3][N], const Real v[3][N], int l) {
  return u[0][l] * v[0][l] + u[1][l] * v[1][l] + u[2][l] * v[2][l];
}

// The nonlinear blend of N triangles from their features (#E blocks of 9 rows) and plane basis
// (6 rows) with weights w (SharedWeights or LaneWeights): writes blend_batch's output (#E + 1
// blocks of 6 rows of N) to out and leaves the rotation in r.
template <typename Real, int N, typename Weights>
MESHIK_LANE_INLINE void blend_nonlinear(const Real* feature, const Real* basis, const Weights& w, int k, Blend blend,
                                        Real* out, BatchRotation<Real, N>& r) {
  blend_rotation(feature, w, k, r);
  // F = R P with P = U + sum_i w_i D_i (affine) or P = sum_i w_i S_i U = (sum_i w_i) U +
  // sum_i w_i D_i (free): the rotated stretch, written as 0 x P + R P.
  Real stretch[6 * N];
  scaled_basis<Real, N>(w, k, blend, basis, stretch);
  for (int i = 0; i < k; ++i)
    for (int e = 0; e < 6 * N; ++e) stretch[e] += w.template at<Real>(i, e % N) * feature[(i * 9 + 3) * N + e];
  const Real zero[3][N] = {};
  cross_plus_rotated(r, zero, stretch, stretch, out);
  // dF/dw_i = psi_i x F (column by column) + R dP/dw_i, psi_i = J_l(phi) phi_i, because
  // d exp(phi)/dw_i = [J_l(phi) phi_i]_x exp(phi) (so3.h); dP/dw_i = D_i (affine), D_i + U (free).
  for (int i = 0; i < k; ++i) {
    Real psi[3][N];
    left_jacobian_times(r, feature + i * 9 * N, psi);
    const Real* stretch_derivative = feature + (i * 9 + 3) * N;
    Real free_derivative[6 * N];
    if (blend == Blend::kFree) {
      for (int e = 0; e < 6 * N; ++e) free_derivative[e] = stretch_derivative[e] + basis[e];
      stretch_derivative = free_derivative;
    }
    cross_plus_rotated(r, psi, out, stretch_derivative, out + (i + 1) * 6 * N);
  }
}

// For N triangles with features `feature` (#E blocks of 9 rows), rotation r, blend output out
// and residuals R_j (6 rows): adds <R_j, d2F_j/dw_a dw_b> to curvature[(a #E + b) N + l] for
// every pair b <= a and lane l.
template <typename Real, int N>
MESHIK_LANE_INLINE void add_curvature(const Real* feature, int k, const BatchRotation<Real, N>& r, const Real* out,
                                      const Real* residual, Real* curvature) {
  Real db[N], dc[N];
  rodrigues_derivative_lanes<N>(r.theta_squared, r.a, r.b, r.c, db, dc);
  // With X(M) = sum_col M_col x R_col, <R, [v]_x M> = v . X(M), and
  //   d2F/dw_a dw_b = [d psi_a / dw_b]_x F + [psi_a]_x dF/dw_b + [psi_b]_x R D_a,
  // so <R, d2F/dw_a dw_b> = (d psi_a/dw_b) . X(F) + psi_a . X(J_b) + psi_b . X(R D_a).
  Real x_f[3][N], x_f_phi[3][N];
  column_cross_sum(out, residual, x_f);
  for (int l = 0; l < N; ++l) {
    x_f_phi[0][l] = x_f[1][l] * r.phi[2][l] - x_f[2][l] * r.phi[1][l];
    x_f_phi[1][l] = x_f[2][l] * r.phi[0][l] - x_f[0][l] * r.phi[2][l];
    x_f_phi[2][l] = x_f[0][l] * r.phi[1][l] - x_f[1][l] * r.phi[0][l];
  }
  // psi_b, X(J_b) and phi . phi_b for a chunk of up to kChunk examples b, then every a >= b
  // against the chunk (the second derivatives are symmetric in a and b).
  constexpr int kChunk = 8;
  const Real two = 2;
  Real psi_chunk[kChunk][3][N], x_j_chunk[kChunk][3][N], phi_v_chunk[kChunk][N];
  for (int b0 = 0; b0 < k; b0 += kChunk) {
    const int chunk = k - b0 < kChunk ? k - b0 : kChunk;
    for (int i = 0; i < chunk; ++i) {
      const Real* v = feature + (b0 + i) * 9 * N;  // phi_b
      left_jacobian_times(r, v, psi_chunk[i]);
      column_cross_sum(out + (b0 + i + 1) * 6 * N, residual, x_j_chunk[i]);
      for (int l = 0; l < N; ++l)
        phi_v_chunk[i][l] = r.phi[0][l] * v[l] + r.phi[1][l] * v[N + l] + r.phi[2][l] * v[2 * N + l];
    }
    for (int a = b0; a < k; ++a) {
      const Real* u = feature + a * 9 * N;  // phi_a
      Real psi_a[3][N], x_rd[3][N], rotated_d[6 * N];
      left_jacobian_times(r, u, psi_a);
      // R D_a = J_a - psi_a x F.
      cross_plus_rotated(r, psi_a, out, static_cast<const Real*>(nullptr), rotated_d);
      for (int e = 0; e < 6 * N; ++e) rotated_d[e] = out[(a + 1) * 6 * N + e] - rotated_d[e];
      column_cross_sum(rotated_d, residual, x_rd);
      // (d psi_a / dw_b) . x, with psi_a = u + b phi x u + c phi x (phi x u) and d phi / dw_b = v:
      //   2 (phi . v) (db pu . x + dc pu . (x x phi))
      //   + b (v x u) . x + c ((v x pu) . x + (v x u) . (x x phi)),       pu = phi x u,
      // is (phi . v) s + v . t with, per a, s = 2 (db pu . x + dc pu . (x x phi)) and
      // t = b (u x x) + c (pu x x + u x (x x phi)) (triple products rotated to isolate v).
      Real s_a[N], t_a[3][N];
      for (int l = 0; l < N; ++l) {
        const Real px = r.phi[0][l], py = r.phi[1][l], pz = r.phi[2][l];
        const Real u0 = u[l], u1 = u[N + l], u2 = u[2 * N + l];
        const Real x0 = x_f[0][l], x1 = x_f[1][l], x2 = x_f[2][l];
        const Real y0 = x_f_phi[0][l], y1 = x_f_phi[1][l], y2 = x_f_phi[2][l];
        const Real pu0 = py * u2 - pz * u1, pu1 = pz * u0 - px * u2, pu2 = px * u1 - py * u0;
        const Real pu_x = pu0 * x0 + pu1 * x1 + pu2 * x2, pu_y = pu0 * y0 + pu1 * y1 + pu2 * y2;
        s_a[l] = two * (db[l] * pu_x + dc[l] * pu_y);
        const Real b = r.b[l], c = r.c[l];
        t_a[0][l] = b * (u1 * x2 - u2 * x1) + c * (pu1 * x2 - pu2 * x1 + u1 * y2 - u2 * y1);
        t_a[1][l] = b * (u2 * x0 - u0 * x2) + c * (pu2 * x0 - pu0 * x2 + u2 * y0 - u0 * y2);
        t_a[2][l] = b * (u0 * x1 - u1 * x0) + c * (pu0 * x1 - pu1 * x0 + u0 * y1 - u1 * y0);
      }
      for (int i = 0; i < chunk && b0 + i <= a; ++i) {
        const int b = b0 + i;
        const Real* v = feature + b * 9 * N;  // phi_b
        Real* acc = curvature + (a * k + b) * N;
        for (int l = 0; l < N; ++l)
          acc[l] += phi_v_chunk[i][l] * s_a[l] + v[l] * t_a[0][l] + v[N + l] * t_a[1][l] +
                    v[2 * N + l] * t_a[2][l] + dot_lane(psi_a, x_j_chunk[i], l) +
                    dot_lane(psi_chunk[i], x_rd, l);
      }
    }
  }
}

// The linear feature L = exp(phi) (D + U) - U of one example for the kLanes triangles of a batch:
// feature, its 9 rows (phi, then D) as stored (float or double, widened here); basis U, 6 rows.
// Writes 6 rows of kLanes to out.
template <typename Stored>
MESHIK_LANE_INLINE void linear_feature(const Stored* feature, const double* basis, double* out) {
  double phi[3][L], theta_squared[L], a[L], b[L], c[L];
  for (int d = 0; d < 3; ++d)
    for (int l = 0; l < L; ++l) phi[d][l] = static_cast<double>(feature[d * L + l]);
  for (int l = 0; l < L; ++l)
    theta_squared[l] = phi[0][l] * phi[0][l] + phi[1][l] * phi[1][l] + phi[2][l] * phi[2][l];
  rodrigues_lanes<L>(theta_squared, a, b, c);
  for (int l = 0; l < L; ++l) {
    double rot[9];
    rodrigues_rotation(phi[0][l], phi[1][l], phi[2][l], a[l], b[l], rot);
    double p[6];  // D + U
    for (int e = 0; e < 6; ++e) p[e] = static_cast<double>(feature[(3 + e) * L + l]) + basis[e * L + l];
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 2; ++col)
        out[(2 * row + col) * L + l] = rot[3 * row] * p[col] + rot[3 * row + 1] * p[2 + col] +
                                       rot[3 * row + 2] * p[4 + col] - basis[(2 * row + col) * L + l];
  }
}

// blend_batch on the features' values stored as Stored (values: those of features), weights w
// (SharedWeights or LaneWeights).
template <typename Stored, typename Weights>
MESHIK_LANE_INLINE void blend_stored(const ExampleFeatures& features, const FeatureValues<Stored>& values,
                                     FeatureSpace space, Blend blend, const Weights& w, int batch, double* out) {
  const int k = features.num_examples;
  const double* basis = features.plane_basis.data() + static_cast<size_t>(batch) * 6 * L;
  const Stored* feature = values.nonlinear.data() + static_cast<size_t>(batch) * k * 9 * L;
  if (batch + kPrefetchDistance < features.num_batches) {
    prefetch_values(feature + kPrefetchDistance * k * 9 * L, static_cast<size_t>(k) * 9 * L);
    prefetch_values(basis + kPrefetchDistance * 6 * L, 6 * L);
  }
  if (space == FeatureSpace::kLinear) {
    // F = s U + sum_i w_i L_i with s = 1 (affine) or sum_i w_i (free: sum_i w_i T_i U).
    scaled_basis<double, L>(w, k, blend, basis, out);
    for (int i = 0; i < k; ++i) {
      double* linear = out + (i + 1) * 6 * L;
      linear_feature(feature + i * 9 * L, basis, linear);
      for (int e = 0; e < 6 * L; ++e) {
        out[e] += w.template at<double>(i, e % L) * linear[e];
        if (blend == Blend::kFree) linear[e] += basis[e];
      }
    }
    return;
  }
  // Floats are widened into out's room after the blend first, in one pass: the blend's loops
  // then read doubles only (reading the floats inside them made the elephant's blend 45 % slower).
  const double* wide = nullptr;
  if constexpr (std::is_same_v<Stored, double>) {
    wide = feature;
  } else {
    double* room = out + 6 * (k + 1) * L;
    for (int e = 0; e < k * 9 * L; ++e) room[e] = static_cast<double>(feature[e]);
    wide = room;
  }
  BatchRotation<double, L> r;
  blend_nonlinear(wide, basis, w, k, blend, out, r);
}

// blend_stored on the features' own precision.
template <typename Weights>
MESHIK_LANE_INLINE void blend_any(const ExampleFeatures& features, FeatureSpace space, Blend blend, const Weights& w,
                                  int batch, double* out) {
  // An explicit branch, not visit_feature_values: a lambda would not share the caller's clones.
  if (features.precision == FeaturePrecision::kSingle)
    blend_stored(features, features.single, space, blend, w, batch, out);
  else
    blend_stored(features, features.full, space, blend, w, batch, out);
}

// Asks for the nonlinear features (values of `features`, as Stored) kCurvatureBatches
// kPrefetchDistance batches ahead of `batch`, and copies those of batch and batch + 1 (zeros if
// it does not exist) into feature: 9 #E rows of 2 kLanes floats (float_pair).
template <typename Stored>
MESHIK_LANE_INLINE void float_feature_pair(const ExampleFeatures& features, const FeatureValues<Stored>& values,
                                           int batch, float* feature) {
  const int k = features.num_examples;
  // A batch's #E blocks of 9 rows are one block of 9 #E rows.
  const Stored* batch_feature = values.nonlinear.data() + static_cast<size_t>(batch) * k * 9 * L;
  if (batch + kCurvatureBatches * kPrefetchDistance < features.num_batches)
    prefetch_values(batch_feature + kCurvatureBatches * kPrefetchDistance * k * 9 * L,
                    static_cast<size_t>(kCurvatureBatches) * k * 9 * L);
  float_pair(batch_feature, batch + 1 < features.num_batches ? batch_feature + k * 9 * L : nullptr, 9 * k, feature);
}

}  // namespace

void linear_features_of_batch(const ExampleFeatures& features, int batch, int example, double* out) {
  const size_t first = (static_cast<size_t>(batch) * features.num_examples + example) * 9 * L;
  const double* basis = features.plane_basis.data() + static_cast<size_t>(batch) * 6 * L;
  visit_feature_values(features, [&](const auto& values) { linear_feature(values.nonlinear.data() + first, basis, out); });
}

MESHIK_SIMD_CLONES
void blend_batch(const ExampleFeatures& features, FeatureSpace space, const double* w, int batch,
                 double* out, Blend blend) {
  blend_any(features, space, blend, SharedWeights{w}, batch, out);
}

MESHIK_SIMD_CLONES
void blend_batch_lanes(const ExampleFeatures& features, FeatureSpace space, Blend blend, const double* lane_weights,
                       int batch, double* out) {
  blend_any(features, space, blend, LaneWeights{lane_weights, L}, batch, out);
}

namespace {

// The nonlinear curvature of batches batch and batch + 1 (add_residual_curvature's arguments,
// weights w: SharedWeights or LaneWeights over 2 kLanes lanes): leaves it per lane in scratch and
// returns it, #E #E rows of 2 kLanes floats (pairs b <= a at row a #E + b; the lanes of batch
// first, then those of batch + 1).
template <typename Weights>
MESHIK_LANE_INLINE const float* pair_curvature(const ExampleFeatures& features, Blend blend, const Weights& w,
                                               int batch, const double* residual, float* scratch) {
  constexpr int N = kCurvatureBatches * L;
  const int k = features.num_examples;
  const bool has_second = batch + 1 < features.num_batches;
  const double* batch_basis = features.plane_basis.data() + static_cast<size_t>(batch) * 6 * L;
  if (batch + kCurvatureBatches * kPrefetchDistance < features.num_batches)
    prefetch_values(batch_basis + kCurvatureBatches * kPrefetchDistance * 6 * L, kCurvatureBatches * 6 * L);
  // scratch: residual (6 rows), features (9 #E rows), plane basis (6 rows), blend output
  // ((#E + 1) 6 rows), curvature (#E #E rows).
  float* narrow_residual = scratch;
  float* feature = narrow_residual + 6 * N;
  float* basis = feature + k * 9 * N;
  float* out = basis + 6 * N;
  float* curvature = out + (k + 1) * 6 * N;
  float_pair(residual, has_second ? residual + 6 * L : nullptr, 6, narrow_residual);
  if (features.precision == FeaturePrecision::kSingle)
    float_feature_pair(features, features.single, batch, feature);
  else
    float_feature_pair(features, features.full, batch, feature);
  float_pair(batch_basis, has_second ? batch_basis + 6 * L : nullptr, 6, basis);
  for (int e = 0; e < k * k * N; ++e) curvature[e] = 0.0f;
  BatchRotation<float, N> r;
  blend_nonlinear(feature, basis, w, k, blend, out, r);
  add_curvature(feature, k, r, out, narrow_residual, curvature);
  return curvature;
}

}  // namespace

MESHIK_SIMD_CLONES
void add_residual_curvature(const ExampleFeatures& features, const double* w, int batch, const double* residual,
                            float* scratch, double* curvature_lanes, Blend blend) {
  constexpr int N = kCurvatureBatches * L;
  const int k = features.num_examples;
  const float* curvature = pair_curvature(features, blend, SharedWeights{w}, batch, residual, scratch);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b <= a; ++b)
      for (int l = 0; l < N; ++l) curvature_lanes[(a * k + b) * L + l % L] += curvature[(a * k + b) * N + l];
}

MESHIK_SIMD_CLONES
const float* residual_curvature_lanes(const ExampleFeatures& features, Blend blend, const double* lane_weights,
                                      int batch, const double* residual, float* scratch) {
  return pair_curvature(features, blend, LaneWeights{lane_weights, kCurvatureBatches * L}, batch, residual, scratch);
}

}  // namespace meshik
