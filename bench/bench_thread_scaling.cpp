// Thread scaling (issue 27): MeshIK on 1, 2, 4, ... threads up to the machine's cores, with the
// parallel efficiency t(1) / (T t(T)) of each column, and the floors as ratios against the
// fastest library factorization measured in the same run, interleaved with it round by round.
//   Elephant (--data elephant-poses: 4 examples, 16 farthest-point handles, targets from pose 5),
//   in one child process, the thread counts and the libraries taking turns in every round:
//     ExampleSet   a cold precompute (the analysis cache cleared first),
//     cached       a second ExampleSet of the same mesh (its analysis from the cache),
//     Solver       building the solver for the handle set on T threads,
//     pose         one whole pose from the linear start (medians over the rounds),
//   and the main thread's CPU time of the Solver and pose (RUSAGE_THREAD: steadier than the wall
//   time under load).
//   1.08M triangles (the horse midpoint-subdivided 3 times, as bench_scaling), each run in a fresh
//   child process (its peak memory its own), the thread counts taking turns:
//     first        ExampleSet + Solver + pose on T threads: the time to the first pose,
//     iteration    one Gauss-Newton iteration (a drag step: the median time between iteration
//                  reports), and the child's peak resident memory.
//   Library: the fastest of CHOLMOD simplicial / supernodal and Eigen SimplicialLDLT (analysis +
//   numeric, one thread, after one untimed warm-up run) on the same system: G'^T G' of the same
//   handles with the 4th-vertex unknowns kept (DESIGN.md's table, the comparison of the issues'
//   floors), and beside it (in brackets) with them eliminated (the smaller system the Solver itself
//   factors).
// Interleaving (the machine's speed drifts by up to 50% from one minute to the next, so a library
// timed once, minutes away from MeshIK, says little): every round is a pair, the library right before
// MeshIK. The elephant's rounds time all three libraries (the fastest of the round counts), then
// MeshIK on each thread count, in one child. The 1.08M's rounds are, per thread count, a child timing
// the library (the one a first full comparison, in a child of its own, found fastest) and then
// MeshIK's child. Each floor is the median of the per-round ratios MeshIK / library of the same
// round, printed with their spread (min-max); the times printed are medians as before.
// Floors (the 2-core machine, 2 threads): elephant Solver <= 0.20x the library, elephant pose
// <= 0.35x, 1.08M first pose <= 0.35x, peak <= 1.0 GB.
//
// Usage: bench_thread_scaling [--data DIR] [--threads 1,2,4] [--rounds N] [--big-rounds N] [--big 0|1]
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "analysis_cache.h"
#include "child_process.h"
#include "library_cholesky.h"
#include "meshik/meshik.h"
#include "normal_matrix.h"
#include "paper_handles.h"
#include "pose_set.h"

namespace {

namespace fs = std::filesystem;
using meshik_bench::PoseSet;

constexpr int kHandles = 16;
constexpr int kMaxCounts = 8;        // thread counts in one table
constexpr double kGigabyteMb = 1024.0;

// The calling thread's CPU time so far (user + system, ms; Linux RUSAGE_THREAD): far steadier than
// the wall time on a shared machine, and on a quiet one the main thread's path bounds the wall time
// of a pass from below.
double thread_cpu_ms() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 + (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e3;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The median of v (the mean of the two middle values for an even count), 0 when empty.
double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t middle = v.size() / 2;
  return v.size() % 2 == 1 ? v[middle] : 0.5 * (v[middle - 1] + v[middle]);
}

// An example set's view and example pointers (the set must outlive them).
struct SetView {
  meshik::MeshView view;
  std::vector<const double*> examples;
  explicit SetView(const PoseSet& s)
      : view{s.rest.vertices.data(), s.rest.num_vertices(), s.rest.triangles.data(), s.rest.num_triangles()} {
    for (const auto& e : s.examples) examples.push_back(e.data());
  }
};

// The ratios ours[r] / library[r] of paired rounds: their median, smallest and largest.
struct RatioSpread {
  double median = 0, min = 0, max = 0;
  int rounds = 0;
};

// ours, library: the times of the same rounds (equal lengths).
RatioSpread ratio_spread(const std::vector<double>& ours, const std::vector<double>& library) {
  std::vector<double> ratios;
  for (size_t r = 0; r < ours.size() && r < library.size(); ++r) ratios.push_back(ours[r] / library[r]);
  RatioSpread out;
  if (ratios.empty()) return out;
  out.median = median(ratios);
  out.min = *std::min_element(ratios.begin(), ratios.end());
  out.max = *std::max_element(ratios.begin(), ratios.end());
  out.rounds = static_cast<int>(ratios.size());
  return out;
}

// The elephant's medians per thread count (indices as `threads`), the Solver's and pose's
// per-round ratios against the library with the 4th vertices kept, and the libraries' medians on
// its system with the 4th vertices kept and eliminated.
struct ElephantTimes {
  double example_set[kMaxCounts] = {}, cached_set[kMaxCounts] = {}, solver[kMaxCounts] = {}, pose[kMaxCounts] = {};
  double solver_main_cpu[kMaxCounts] = {}, pose_main_cpu[kMaxCounts] = {};  // the main thread's CPU ms
  RatioSpread solver_ratio[kMaxCounts], pose_ratio[kMaxCounts];
  int iterations = 0;
  meshik_bench::LibraryFactor library, eliminated_library;
};

// The fastest library's factorization of a (one run after a warm-up); its time appended to `times`.
meshik_bench::LibraryFactor time_library(const meshik::CscMatrix& a, std::vector<double>& times) {
  const meshik_bench::LibraryFactor fastest = meshik_bench::fastest_library_factor(a, 1);
  times.push_back(fastest.ms);
  return fastest;
}

ElephantTimes time_elephant(const PoseSet& set, const std::vector<int>& threads, int rounds) {
  const SetView input(set);
  const std::vector<int> handles = meshik_bench::farthest_point_handles(set.rest.vertices, kHandles);
  const std::vector<double> targets = meshik_bench::gather_rows(set.held_out, handles);
  const size_t counts = threads.size();
  std::vector<std::vector<double>> cold(counts), cached(counts), solver(counts), pose(counts);
  std::vector<std::vector<double>> solver_cpu(counts), pose_cpu(counts);
  const meshik::CscMatrix kept = meshik_bench::deformation_normal_matrix(set.rest, handles, true);
  const meshik::CscMatrix eliminated = meshik_bench::deformation_normal_matrix(set.rest, handles, false);
  std::vector<double> kept_ms, eliminated_ms;
  ElephantTimes out;
  for (int round = 0; round < rounds; ++round) {
    out.library = time_library(kept, kept_ms);
    out.eliminated_library = time_library(eliminated, eliminated_ms);
    for (size_t c = 0; c < counts; ++c) {
      meshik::clear_analysis_cache();
      auto start = std::chrono::steady_clock::now();
      auto examples = std::make_shared<meshik::ExampleSet>(input.view, input.examples, meshik::ProgressCallback{},
                                                            threads[c]);
      cold[c].push_back(ms_since(start));
      start = std::chrono::steady_clock::now();
      examples = std::make_shared<meshik::ExampleSet>(input.view, input.examples, meshik::ProgressCallback{},
                                                       threads[c]);
      cached[c].push_back(ms_since(start));
      meshik::SolverOptions options;
      options.threads = threads[c];
      double cpu = thread_cpu_ms();
      start = std::chrono::steady_clock::now();
      const meshik::Solver built(examples, handles, options);
      solver[c].push_back(ms_since(start));
      solver_cpu[c].push_back(thread_cpu_ms() - cpu);
      cpu = thread_cpu_ms();
      start = std::chrono::steady_clock::now();
      out.iterations = built.solve(targets.data()).iterations;
      pose[c].push_back(ms_since(start));
      pose_cpu[c].push_back(thread_cpu_ms() - cpu);
    }
  }
  out.library.ms = median(kept_ms);
  out.eliminated_library.ms = median(eliminated_ms);
  for (size_t c = 0; c < counts; ++c) {
    out.example_set[c] = median(cold[c]);
    out.cached_set[c] = median(cached[c]);
    out.solver[c] = median(solver[c]);
    out.pose[c] = median(pose[c]);
    out.solver_main_cpu[c] = median(solver_cpu[c]);
    out.pose_main_cpu[c] = median(pose_cpu[c]);
    out.solver_ratio[c] = ratio_spread(solver[c], kept_ms);
    out.pose_ratio[c] = ratio_spread(pose[c], kept_ms);
  }
  return out;
}

// One run of the large set on `threads` threads, in a fresh process.
struct FirstPose {
  double example_set_ms = 0, solver_ms = 0, pose_ms = 0, iteration_ms = 0, peak_mb = 0;
  int triangles = 0;
};

FirstPose first_pose(const PoseSet& set, int threads) {
  const SetView input(set);
  const std::vector<int> handles = meshik_bench::farthest_point_handles(set.rest.vertices, kHandles);
  const std::vector<double> targets = meshik_bench::gather_rows(set.held_out, handles);
  FirstPose out;
  out.triangles = set.rest.num_triangles();
  auto start = std::chrono::steady_clock::now();
  const auto examples =
      std::make_shared<meshik::ExampleSet>(input.view, input.examples, meshik::ProgressCallback{}, threads);
  out.example_set_ms = ms_since(start);
  meshik::SolverOptions options;
  options.threads = threads;
  start = std::chrono::steady_clock::now();
  const meshik::Solver solver(examples, handles, options);
  out.solver_ms = ms_since(start);
  std::vector<std::chrono::steady_clock::time_point> reports;
  start = std::chrono::steady_clock::now();
  solver.solve(targets.data(), nullptr, [&](double, const std::string&) {
    reports.push_back(std::chrono::steady_clock::now());
    return true;
  });
  out.pose_ms = ms_since(start);
  std::vector<double> intervals;
  for (size_t i = 1; i < reports.size(); ++i)
    intervals.push_back(std::chrono::duration<double, std::milli>(reports[i] - reports[i - 1]).count());
  out.iteration_ms = median(intervals);
  out.peak_mb = meshik_bench::peak_rss_mb();
  return out;
}

// The set's system (handles as the Solver's; the lower triangle).
meshik::CscMatrix handle_system(const PoseSet& set, bool keep_fourth_vertices) {
  const std::vector<int> handles = meshik_bench::farthest_point_handles(set.rest.vertices, kHandles);
  return meshik_bench::deformation_normal_matrix(set.rest, handles, keep_fourth_vertices);
}

// "1,2,4" -> {1, 2, 4}; empty: 1, 2, 4, ... below the cores, then the cores.
std::vector<int> thread_counts(const std::string& list, int cores) {
  std::vector<int> counts;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (std::atoi(item.c_str()) > 0) counts.push_back(std::atoi(item.c_str()));
  if (counts.empty()) {
    for (int t = 1; t < cores; t *= 2) counts.push_back(t);
    counts.push_back(cores);
  }
  if (counts.size() > kMaxCounts) counts.resize(kMaxCounts);
  return counts;
}

// "12.3 (87%)": a time and its parallel efficiency against one thread's.
std::string with_efficiency(double ms, double one_thread_ms, int threads) {
  char text[48];
  if (one_thread_ms > 0 && ms > 0)
    std::snprintf(text, sizeof text, "%8.1f %4.0f%%", ms, 100.0 * one_thread_ms / (threads * ms));
  else
    std::snprintf(text, sizeof text, "%8.1f %5s", ms, "-");
  return text;
}

// "name: ours ms / library ms (library) medians; per-round ratio median x (min-max, N rounds) <=
// floor: met|MISSED", the floor judged on the median of the per-round ratios.
std::string floor_line(const char* what, double ours_ms, const meshik_bench::LibraryFactor& library,
                       const RatioSpread& ratio, double floor) {
  char line[320];
  std::snprintf(line, sizeof line,
                "%s: %.1f ms / %.1f ms (%s), medians; per-round ratio median %.3fx (%.3f-%.3f, %d rounds) "
                "<= %.2fx: %s",
                what, ours_ms, library.ms, library.name, ratio.median, ratio.min, ratio.max, ratio.rounds, floor,
                ratio.median <= floor ? "met" : "MISSED");
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", list;
  int rounds = 7, big_rounds = 3;
  bool big = true;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--data") data = argv[i + 1];
    else if (key == "--threads") list = argv[i + 1];
    else if (key == "--rounds") rounds = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--big-rounds") big_rounds = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--big") big = std::atoi(argv[i + 1]) != 0;
    else if (key != "--samples") std::fprintf(stderr, "ignoring unknown option %s\n", key.c_str());
  }
  const PoseSet elephant = meshik_bench::read_pose_set(fs::path(data) / "elephant-poses");
  const PoseSet horse = meshik_bench::read_pose_set(fs::path(data) / "horse-poses");
  if (elephant.rest.num_vertices() == 0 || horse.rest.num_vertices() == 0) {
    std::printf("(skipping: elephant-poses or horse-poses not found under %s)\n", data.c_str());
    return 0;
  }
  const int cores = static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
  const std::vector<int> threads = thread_counts(list, cores);
  double load[3] = {};
  if (getloadavg(load, 3) < 0) load[0] = -1;
  std::printf("Thread scaling on %d cores (load average %.2f when started); times in ms, medians; (%%): parallel\n"
              "efficiency t(1) / (T t(T)). Elephant: %d rounds; 1.08M: %d fresh processes per thread count.\n\n",
              cores, load[0], rounds, big_rounds);
  // The 1.08M's full library comparisons first, each in its own process (the parent never starts
  // OpenMP): the fastest library, timed again in every round, and the eliminated system's.
  meshik_bench::LibraryFactor big_library, big_eliminated_library;
  const PoseSet large = big ? meshik_bench::subdivided(horse, 3) : PoseSet();
  const bool compared =
      !big ||
      (meshik_bench::in_child([&] { return meshik_bench::fastest_library_factor(handle_system(large, true), 1); },
                              big_library) &&
       meshik_bench::in_child([&] { return meshik_bench::fastest_library_factor(handle_system(large, false), 1); },
                              big_eliminated_library));
  if (!compared) {
    std::printf("(a library comparison failed)\n");
    return 1;
  }
  ElephantTimes e;
  if (!meshik_bench::in_child([&] { return time_elephant(elephant, threads, rounds); }, e)) {
    std::printf("(the elephant's child failed)\n");
    return 1;
  }
  const meshik_bench::LibraryFactor& elephant_library = e.library;
  const meshik_bench::LibraryFactor& elephant_eliminated_library = e.eliminated_library;
  // The 1.08M's rounds: per thread count, the library's child, then MeshIK's.
  std::vector<std::vector<FirstPose>> runs(threads.size());
  std::vector<std::vector<double>> paired_library_ms(threads.size()), paired_first_ms(threads.size());
  std::vector<double> big_library_ms;
  for (int round = 0; big && round < big_rounds; ++round)
    for (size_t c = 0; c < threads.size(); ++c) {
      meshik_bench::LibraryFactor library;
      FirstPose run;
      if (!meshik_bench::in_child(
              [&] { return meshik_bench::one_library_factor(handle_system(large, true), big_library.index, 1); },
              library)) {
        std::printf("(1.08M library before %d threads: the child failed)\n", threads[c]);
      } else if (!meshik_bench::in_child([&] { return first_pose(large, threads[c]); }, run)) {
        std::printf("(1.08M on %d threads: the child failed)\n", threads[c]);
      } else {
        runs[c].push_back(run);
        big_library_ms.push_back(library.ms);
        paired_library_ms[c].push_back(library.ms);
        paired_first_ms[c].push_back(run.example_set_ms + run.solver_ms + run.pose_ms);
      }
    }
  if (!big_library_ms.empty()) big_library.ms = median(big_library_ms);
  std::vector<FirstPose> big_median(threads.size());  // each phase's median
  std::vector<double> big_first(threads.size());       // the first pose's median
  for (size_t c = 0; c < threads.size(); ++c) {
    std::vector<double> first, example_set, solver, pose, iteration, peak;
    for (const FirstPose& r : runs[c]) {
      first.push_back(r.example_set_ms + r.solver_ms + r.pose_ms);
      example_set.push_back(r.example_set_ms);
      solver.push_back(r.solver_ms);
      pose.push_back(r.pose_ms);
      iteration.push_back(r.iteration_ms);
      peak.push_back(r.peak_mb);
      big_median[c].triangles = r.triangles;
    }
    big_median[c].example_set_ms = median(example_set);
    big_median[c].solver_ms = median(solver);
    big_median[c].pose_ms = median(pose);
    big_median[c].iteration_ms = median(iteration);
    big_median[c].peak_mb = peak.empty() ? 0 : *std::max_element(peak.begin(), peak.end());
    big_first[c] = median(first);
  }
  std::printf("%7s | %14s %9s %14s %14s | %14s %8s %8s %8s %9s %8s\n", "threads", "elephant set", "cached",
              "Solver", "pose", "1.08M first", "set", "Solver", "pose", "iteration", "peak MB");
  for (size_t c = 0; c < threads.size(); ++c) {
    const FirstPose& b = big_median[c];
    const bool one = threads[0] == 1;
    std::printf("%7d | %s %9.1f %s %s | %s %8.0f %8.0f %8.0f %9.1f %8.0f\n", threads[c],
                with_efficiency(e.example_set[c], one ? e.example_set[0] : 0, threads[c]).c_str(),
                e.cached_set[c], with_efficiency(e.solver[c], one ? e.solver[0] : 0, threads[c]).c_str(),
                with_efficiency(e.pose[c], one ? e.pose[0] : 0, threads[c]).c_str(),
                with_efficiency(big_first[c], one ? big_first[0] : 0, threads[c]).c_str(), b.example_set_ms, b.solver_ms,
                b.pose_ms, b.iteration_ms, b.peak_mb);
  }
  std::printf("\nLibrary (fastest, analysis + numeric, 1 thread; medians over the rounds), 4th vertices kept\n"
              "[eliminated]: elephant %.1f ms (%s) [%.1f ms, %s]",
              elephant_library.ms, elephant_library.name, elephant_eliminated_library.ms,
              elephant_eliminated_library.name);
  if (big)
    std::printf(", 1.08M %.0f ms (%s, %zu runs, each before a MeshIK run) [%.0f ms, %s, once]", big_library.ms,
                big_library.name, big_library_ms.size(), big_eliminated_library.ms, big_eliminated_library.name);
  std::printf("; elephant pose: %d iterations\n", e.iterations);
  std::printf("Elephant, the main thread's CPU time (medians, ms; steadier than the wall time under load):");
  for (size_t c = 0; c < threads.size(); ++c)
    std::printf("%s %d threads Solver %.1f pose %.1f", c == 0 ? "" : ";", threads[c], e.solver_main_cpu[c],
                e.pose_main_cpu[c]);
  std::printf("\n");
  const auto two = std::find(threads.begin(), threads.end(), 2);
  if (two == threads.end()) return 0;
  const size_t c = static_cast<size_t>(two - threads.begin());
  std::printf("\nFloors (2 threads; the median of the per-round ratios MeshIK / library of the same round,\n"
              "on the system with 4th vertices kept; in brackets the ratio of the medians against the one\n"
              "with them eliminated):\n");
  std::printf("  %s [%.3fx]\n",
              floor_line("elephant Solver", e.solver[c], elephant_library, e.solver_ratio[c], 0.20).c_str(),
              e.solver[c] / elephant_eliminated_library.ms);
  std::printf("  %s [%.3fx]\n", floor_line("elephant pose", e.pose[c], elephant_library, e.pose_ratio[c], 0.35).c_str(),
              e.pose[c] / elephant_eliminated_library.ms);
  if (big && !runs[c].empty()) {
    const FirstPose& b = big_median[c];
    const RatioSpread first_ratio = ratio_spread(paired_first_ms[c], paired_library_ms[c]);
    meshik_bench::LibraryFactor paired_library = big_library;  // its runs beside the 2-thread ones
    paired_library.ms = median(paired_library_ms[c]);
    std::printf("  %s [%.3fx]\n",
                floor_line("1.08M first pose", big_first[c], paired_library, first_ratio, 0.35).c_str(),
                big_first[c] / big_eliminated_library.ms);
    std::printf("  1.08M peak memory %.0f MB <= %.0f MB (1.0 GB): %s\n", b.peak_mb, kGigabyteMb,
                b.peak_mb <= kGigabyteMb ? "met" : "MISSED");
  }
  return 0;
}
