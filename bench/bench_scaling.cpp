// Scaling of MeshIK with mesh size: the horse (--data, ../shared/data/horse-poses, 4 examples,
// targets from the held-out pose 5 at 16 farthest-point handles) midpoint-subdivided 1, 2 and 3
// times (about 67k, 270k and 1.08M triangles), on one thread and on all cores (the ExampleSet, the
// Solver and its poses alike). Per size and thread count, in a fresh child process each (so that
// its peak memory is its own):
//   ExampleSet  the precompute (its phases on the next line),
//   Solver      building the solver for the handle set (assembly, numeric factorization on the
//               pattern the ExampleSet analysed, the linear start),
//   iteration   one Gauss-Newton iteration (median time between consecutive iteration reports),
//   pose        one whole pose from the linear start to convergence,
//   first       ExampleSet + Solver + pose: time to the first pose,
//   peak RSS    the child's peak resident memory (also as it was after the ExampleSet, and the
//               resident memory before it: the program and its input meshes), and the
//               ExampleSet's own arrays per triangle (the system's pattern counted, the rest of
//               its symbolic analysis not) and the features' per triangle and example.
// The features are stored in single precision (the library's default) or, with --precision double,
// in double (the comparison for the memory and times).
// In the same run, the same-sized normal matrix G'^T G' (4th vertices eliminated, handles
// removed) is factored by MeshIK's sparse Cholesky and by CHOLMOD and Eigen (library_cholesky.h):
// the fastest library's factor time (analysis + numeric) is the comparison for Solver.
//
// Usage: bench_scaling [--data DIR] [--levels N] [--first-level N] [--reps N] [--precision single|double]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "child_process.h"
#include "example_set_impl.h"
#include "library_cholesky.h"
#include "meshik/meshik.h"
#include "normal_matrix.h"
#include "paper_handles.h"
#include "pose_set.h"

namespace {

namespace fs = std::filesystem;
using meshik_bench::PoseSet;
using meshik_bench::current_rss_mb;
using meshik_bench::in_child;
using meshik_bench::peak_rss_mb;
using meshik_bench::subdivided;

constexpr int kHandles = 16;

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template <typename T, typename Allocator>
size_t bytes_of(const std::vector<T, Allocator>& v) {
  return v.capacity() * sizeof(T);
}

// Bytes of an ExampleSet's arrays (the system's pattern counted, the rest of its symbolic
// analysis not): all, and the part that grows with the number of examples (the features).
void example_set_bytes(const meshik::ExampleSet::Impl& s, double& all, double& per_example) {
  const meshik::ExampleFeatures& f = s.features;
  const meshik::CscMatrix& pattern = s.system_analysis.analyzed_pattern();
  per_example = static_cast<double>(bytes_of(f.single.nonlinear) + bytes_of(f.full.nonlinear));
  all = per_example + static_cast<double>(
      bytes_of(f.plane_basis) + bytes_of(s.vertex_of_internal) + bytes_of(s.internal_of_vertex) +
      bytes_of(s.triangle_of_internal) + bytes_of(s.rest) + bytes_of(s.triangles) +
      bytes_of(s.components.component_of_vertex) + bytes_of(s.frames.gradient) + bytes_of(s.frames.plane_basis) +
      bytes_of(s.system_row_of_vertex) + bytes_of(pattern.col_start) + bytes_of(pattern.row_index) +
      bytes_of(s.system_values));
}

// What one child measures (sent to the parent through a pipe as raw bytes).
struct Measurement {
  int triangles = 0, iterations = 0;
  double example_set_ms = 0, solver_ms = 0, iteration_ms = -1, pose_ms = 0, peak_mb = 0, set_peak_mb = 0;
  double input_mb = 0;  // resident before the ExampleSet: the program and the subdivided input meshes
  double set_bytes_per_triangle = 0, feature_bytes_per_triangle_example = 0;
  char phases[512] = {};
};

Measurement measure(const PoseSet& base, int levels, int threads, int reps, meshik::FeaturePrecision precision) {
  Measurement out;
  const PoseSet set = subdivided(base, levels);
  std::vector<const double*> pointers;
  for (const auto& e : set.examples) pointers.push_back(e.data());
  const meshik::MeshView view{set.rest.vertices.data(), set.rest.num_vertices(), set.rest.triangles.data(),
                              set.rest.num_triangles()};
  out.triangles = set.rest.num_triangles();
  out.input_mb = current_rss_mb();
  auto start = std::chrono::steady_clock::now();
  const auto examples =
      std::make_shared<meshik::ExampleSet>(view, pointers, meshik::ProgressCallback{}, threads, precision);
  out.example_set_ms = ms_since(start);
  out.set_peak_mb = peak_rss_mb();
  int written = 0;
  for (const auto& [name, ms] : examples->impl().phase_times)
    written += std::snprintf(out.phases + written, sizeof out.phases - written, "%s %.0f, ", name.c_str(), ms);
  double all = 0, per_example = 0;
  example_set_bytes(examples->impl(), all, per_example);
  out.set_bytes_per_triangle = all / out.triangles;
  out.feature_bytes_per_triangle_example = per_example / (out.triangles * static_cast<double>(pointers.size()));
  const std::vector<int> handles = meshik_bench::farthest_point_handles(set.rest.vertices, kHandles);
  const std::vector<double> targets = meshik_bench::gather_rows(set.held_out, handles);
  meshik::SolverOptions options;
  options.threads = threads;  // the Solver and its poses on the row's threads too
  start = std::chrono::steady_clock::now();
  const meshik::Solver solver(examples, handles, options);
  out.solver_ms = ms_since(start);
  std::vector<double> poses, intervals;
  for (int r = 0; r < reps; ++r) {
    std::vector<std::chrono::steady_clock::time_point> reports;
    start = std::chrono::steady_clock::now();
    const meshik::SolveResult result = solver.solve(targets.data(), nullptr, [&](double, const std::string&) {
      reports.push_back(std::chrono::steady_clock::now());
      return true;
    });
    poses.push_back(ms_since(start));
    out.iterations = result.iterations;
    for (size_t i = 1; i < reports.size(); ++i)
      intervals.push_back(std::chrono::duration<double, std::milli>(reports[i] - reports[i - 1]).count());
  }
  std::sort(poses.begin(), poses.end());
  out.pose_ms = poses[poses.size() / 2];
  if (!intervals.empty()) {
    std::sort(intervals.begin(), intervals.end());
    out.iteration_ms = intervals[intervals.size() / 2];
  }
  out.peak_mb = peak_rss_mb();
  return out;
}

// The libraries' and MeshIK's factorization of the size's normal matrix (single thread).
struct FactorComparison {
  double ours_ms = 0, fastest_ms = 0;
  char fastest[64] = {};
};

FactorComparison compare_factor(const PoseSet& base, int levels) {
  const PoseSet set = subdivided(base, levels);
  const std::vector<int> handles = meshik_bench::farthest_point_handles(set.rest.vertices, kHandles);
  const meshik::CscMatrix a = meshik_bench::deformation_normal_matrix(set.rest, handles, false);
  const Eigen::SparseMatrix<double> full = meshik_bench::full_matrix(a);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(a.rows, 15);
  const int reps = 1;
  const meshik_bench::Result ours = meshik_bench::bench_meshik(a, b, full, reps);
  const std::vector<meshik_bench::Result> theirs = meshik_bench::bench_libraries(a, b, full, reps);
  const auto fastest = meshik_bench::fastest_factor(theirs);
  FactorComparison out;
  out.ours_ms = ours.analyze_ms + ours.numeric_ms;
  out.fastest_ms = fastest->analyze_ms + fastest->numeric_ms;
  std::snprintf(out.fastest, sizeof out.fastest, "%s", fastest->name.c_str());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data";
  int levels = 3, first_level = 1, reps = 3;
  meshik::FeaturePrecision precision = meshik::FeaturePrecision::kSingle;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--data") data = argv[i + 1];
    else if (key == "--levels") levels = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--first-level") first_level = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--reps") reps = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--precision" && std::string(argv[i + 1]) == "double") precision = meshik::FeaturePrecision::kDouble;
    else if (key == "--precision" && std::string(argv[i + 1]) == "single") precision = meshik::FeaturePrecision::kSingle;
    else if (key != "--samples") std::fprintf(stderr, "ignoring unknown option %s\n", key.c_str());
  }
  const fs::path folder = fs::path(data) / "horse-poses";
  const PoseSet base = meshik_bench::read_pose_set(folder);
  if (base.rest.num_vertices() == 0) {
    std::printf("(skipping: %s not found)\n", (folder / "reference.obj").c_str());
    return 0;
  }
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  std::printf("Horse midpoint-subdivided, 4 examples, %d handles, targets from pose 5; %ld cores; times in ms,\n"
              "pose: median of %d solves; Lib factor: fastest of CHOLMOD simplicial/supernodal and Eigen\n"
              "SimplicialLDLT on the same-sized normal matrix (analysis + numeric, 1 thread), Ours: MeshIK's\n"
              "sparse Cholesky on it (analysis + numeric). Features stored in %s precision.\n\n", kHandles, cores, reps,
              precision == meshik::FeaturePrecision::kSingle ? "single" : "double");
  std::printf("%10s %7s | %10s %8s %9s %8s %9s | %9s %9s | %8s %8s %8s | %s\n", "triangles", "threads", "ExampleSet",
              "Solver", "iteration", "pose", "first", "peak MB", "set B/tri", "Ours", "Lib", "Ours/Lib", "library");
  std::vector<std::string> floors;
  for (int level = first_level; level <= levels; ++level) {
    FactorComparison factor;
    const bool compared = in_child([&] { return compare_factor(base, level); }, factor);
    std::vector<Measurement> rows;
    for (int threads : {1, 0}) {
      Measurement m;
      if (!in_child([&] { return measure(base, level, threads, reps, precision); }, m)) {
        std::printf("(level %d, threads %d: the child failed)\n", level, threads);
        continue;
      }
      const double first = m.example_set_ms + m.solver_ms + m.pose_ms;
      std::printf("%10d %7s | %10.0f %8.0f %9.1f %8.0f %9.0f | %9.0f %9.0f | %8.0f %8.0f %8.2f | %s\n", m.triangles,
                  threads == 1 ? "1" : "all", m.example_set_ms, m.solver_ms, m.iteration_ms, m.pose_ms, first,
                  m.peak_mb, m.set_bytes_per_triangle, compared ? factor.ours_ms : 0.0,
                  compared ? factor.fastest_ms : 0.0, compared ? factor.ours_ms / factor.fastest_ms : 0.0,
                  compared ? factor.fastest : "-");
      std::printf("%18s ExampleSet phases: %s%d iterations, features %.0f B per triangle and example, "
                  "peak RSS after the ExampleSet %.0f MB, before it %.0f MB (the input meshes)\n", "", m.phases,
                  m.iterations, m.feature_bytes_per_triangle_example, m.set_peak_mb, m.input_mb);
      if (level == 3 && threads == 0) {
        char line[200];
        std::snprintf(line, sizeof line, "1.08M triangles, all cores: ExampleSet + Solver + first pose %.0f ms <= 3000: %s; "
                      "peak memory %.0f MB <= 1229: %s", first, first <= 3000 ? "met" : "MISSED", m.peak_mb,
                      m.peak_mb <= 1229 ? "met" : "MISSED");
        floors.push_back(line);
      }
      std::fflush(stdout);
    }
  }
  for (const std::string& line : floors) std::printf("\nFloor: %s\n", line.c_str());
  return 0;
}
