// The paper's timing table (Sumner et al. 2005, Table 1) beside MeshIK's own figures on the same
// meshes: lion, horse and elephant from --data (../shared/data) and the generated example sets in
// --samples (sample_meshes/). On one thread, and on all cores (the nT columns: the solver's default
// threads = 0), both measured alternately in the same run. For each mesh:
//   Factor  = building the Solver for a handle set (assembly of G'^T G' with identity rows for the
//             handles, its numeric factorization on the mesh's pattern, whose ordering and
//             symbolic analysis the ExampleSet did once, and the linear start),
//   Solve   = one Gauss-Newton iteration (a solve stopped after one iteration minus one stopped
//             before the first: the second-order pass, one evaluation with its solve, the step),
//   Total   = one whole pose, from the linear-space start weights to convergence,
// each the median of several runs, with the paper's seconds and the speed-up (paper / ours).
// The in-run comparison: the factorization (with its own ordering) of G'^T G' with the fourth
// vertices kept (not eliminated).
// Handles: 16 vertices by farthest-point sampling; targets: a held-out pose (not an example).
// --precision single|double: how the ExampleSet stores the features (default single, the library's).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "gradient_operator.h"
#include "meshik/meshik.h"
#include "meshik/sparse_cholesky.h"
#include "obj_reader.h"
#include "paper_handles.h"
#include "triangle_frames.h"

namespace {

namespace fs = std::filesystem;

struct PaperRow {
  const char* name;
  const char* verts;
  const char* tris;
  int examples;
  double factor, solve, total;  // seconds, 3.4 GHz Pentium 4
};

const PaperRow kPaper[] = {{"Bar", "132", "260", 2, 0.000, 0.000, 0.015},
                           {"Flag", "516", "932", 14, 0.016, 0.015, 0.020},
                           {"Lion", "5,000", "9,996", 10, 0.475, 0.150, 0.210},
                           {"Horse", "8,425", "16,846", 4, 0.610, 0.105, 0.160},
                           {"Elephant", "42,321", "84,638", 4, 13.249, 0.620, 0.906}};

// An example set to time: rest mesh, examples, and the held-out pose giving the targets.
struct Case {
  std::string name;
  const PaperRow* paper = nullptr;
  meshik_bench::TriangleMesh rest;
  std::vector<std::vector<double>> examples;
  std::vector<double> held_out;
  std::string note;
};

struct Timing {
  // One thread, and all cores (threaded_*).
  double precompute_ms = 0, factor_ms = 0, kept_factor_ms = 0, iteration_ms = 0, pose_ms = 0;
  double threaded_factor_ms = 0, threaded_iteration_ms = 0, threaded_pose_ms = 0;
  int iterations = 0;
  double pose_error = 0;  // RMS vertex distance to the held-out pose / bounding-box diagonal
};

double milliseconds_of(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Median time of `repeats` runs of work, in milliseconds.
double median_ms(int repeats, const std::function<void()>& work) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) times.push_back(milliseconds_of(work));
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// Medians of `repeats` runs of each of two works, run alternately (a, b, a, b, ...) so that both
// see the same load of the machine; in milliseconds, a's then b's.
std::pair<double, double> alternate_median_ms(int repeats, const std::function<void()>& a,
                                              const std::function<void()>& b) {
  std::vector<double> times_a, times_b;
  for (int r = 0; r < repeats; ++r) {
    times_a.push_back(milliseconds_of(a));
    times_b.push_back(milliseconds_of(b));
  }
  std::sort(times_a.begin(), times_a.end());
  std::sort(times_b.begin(), times_b.end());
  return {times_a[times_a.size() / 2], times_b[times_b.size() / 2]};
}

// Factor time of G'^T G' with the fourth vertices kept as unknowns (#V - #H + #F), for comparison.
double kept_factor_ms(const meshik_bench::TriangleMesh& mesh, const std::vector<int>& handles,
                      int repeats) {
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  const meshik::TriangleFrames frames =
      meshik::compute_triangle_frames(mesh.vertices.data(), mesh.triangles.data(), m);
  std::vector<int> unknown(n + m, 0);
  for (int h : handles) unknown[h] = -1;
  int count = 0;
  for (int& u : unknown) u = u < 0 ? -1 : count++;
  // Columns of G' per row (each row of G touches 4 columns); lower triangle of G'^T G'.
  const std::vector<meshik::MatrixEntry> g = meshik::kept_gradient_operator(frames, mesh.triangles.data(), n);
  std::vector<std::vector<std::pair<int, double>>> columns(count);
  for (size_t row_start = 0; row_start < g.size(); row_start += 4)
    for (size_t a = row_start; a < row_start + 4; ++a)
      for (size_t b = row_start; b < row_start + 4; ++b) {
        const int i = unknown[g[a].col], j = unknown[g[b].col];
        if (i >= 0 && j >= 0 && i >= j) columns[j].push_back({i, g[a].value * g[b].value});
      }
  meshik::CscMatrix lower;
  lower.rows = lower.cols = count;
  lower.col_start.push_back(0);
  for (auto& column : columns) {
    std::sort(column.begin(), column.end());
    for (size_t s = 0; s < column.size(); ++s) {
      if (s > 0 && column[s].first == column[s - 1].first) {
        lower.values.back() += column[s].second;
      } else {
        lower.row_index.push_back(column[s].first);
        lower.values.push_back(column[s].second);
      }
    }
    lower.col_start.push_back(static_cast<int>(lower.row_index.size()));
  }
  return median_ms(repeats, [&] {
    meshik::SparseCholesky factor;
    factor.compute(lower);
  });
}

Timing time_case(const Case& c, int repeats, meshik::FeaturePrecision precision) {
  Timing t;
  std::vector<const double*> pointers;
  for (const auto& e : c.examples) pointers.push_back(e.data());
  const meshik::MeshView view{c.rest.vertices.data(), c.rest.num_vertices(), c.rest.triangles.data(),
                              c.rest.num_triangles()};
  std::shared_ptr<meshik::ExampleSet> set;
  t.precompute_ms = milliseconds_of(
      [&] { set = std::make_shared<meshik::ExampleSet>(view, pointers, meshik::ProgressCallback{}, 0, precision); });
  const std::vector<int> handles = meshik_bench::farthest_point_handles(c.rest.vertices, 16);
  const std::vector<double> targets = meshik_bench::gather_rows(c.held_out, handles);
  meshik::SolverOptions serial, threaded;
  serial.threads = 1;
  threaded.threads = 0;
  std::unique_ptr<meshik::Solver> solver, threaded_solver;
  std::tie(t.factor_ms, t.threaded_factor_ms) = alternate_median_ms(
      repeats, [&] { solver = std::make_unique<meshik::Solver>(set, handles, serial); },
      [&] { threaded_solver = std::make_unique<meshik::Solver>(set, handles, threaded); });
  t.kept_factor_ms = kept_factor_ms(c.rest, handles, repeats);
  meshik::SolveResult result;
  std::tie(t.pose_ms, t.threaded_pose_ms) = alternate_median_ms(
      repeats, [&] { result = solver->solve(targets.data()); }, [&] { threaded_solver->solve(targets.data()); });
  t.iterations = result.iterations;
  // One iteration: a solve stopped after one iteration minus one stopped before the first.
  serial.max_iterations = threaded.max_iterations = 0;
  const meshik::Solver before_first(set, handles, serial), threaded_before_first(set, handles, threaded);
  serial.max_iterations = threaded.max_iterations = 1;
  const meshik::Solver after_first(set, handles, serial), threaded_after_first(set, handles, threaded);
  const auto after = alternate_median_ms(repeats, [&] { after_first.solve(targets.data()); },
                                         [&] { threaded_after_first.solve(targets.data()); });
  const auto before = alternate_median_ms(repeats, [&] { before_first.solve(targets.data()); },
                                          [&] { threaded_before_first.solve(targets.data()); });
  t.iteration_ms = after.first - before.first;
  t.threaded_iteration_ms = after.second - before.second;
  double sum = 0;
  for (size_t e = 0; e < result.vertices.size(); ++e)
    sum += (result.vertices[e] - c.held_out[e]) * (result.vertices[e] - c.held_out[e]);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t e = 0; e < c.held_out.size(); ++e) {
    lo[e % 3] = std::min(lo[e % 3], c.held_out[e]);
    hi[e % 3] = std::max(hi[e % 3], c.held_out[e]);
  }
  const double diagonal = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  t.pose_error = std::sqrt(sum / c.rest.num_vertices()) / diagonal;
  return t;
}

// A shared/data folder: reference.obj, examples by number, one held-out pose.
bool load_data_case(const std::string& data, const char* folder, const PaperRow* paper,
                    std::vector<int> example_numbers, int held_out, Case& c) {
  const fs::path dir = fs::path(data) / folder;
  if (!fs::exists(dir / "reference.obj")) {
    std::printf("(skipping %s: %s not found)\n", folder, (dir / "reference.obj").c_str());
    return false;
  }
  c.name = paper->name;
  c.paper = paper;
  c.rest = meshik_bench::read_obj((dir / "reference.obj").string());
  for (int k : example_numbers)
    c.examples.push_back(meshik_bench::read_obj((dir / (std::to_string(k) + ".obj")).string()).vertices);
  c.held_out = meshik_bench::read_obj((dir / (std::to_string(held_out) + ".obj")).string()).vertices;
  c.note = std::string(folder) + ": examples";
  for (int k : example_numbers) c.note += " " + std::to_string(k);
  c.note += ", targets from pose " + std::to_string(held_out);
  return true;
}

// A sample_meshes/ folder: rest.obj and example_*.obj. The last example is held out when there are
// three or more; otherwise the targets come from the mean of the examples.
bool load_sample_case(const fs::path& dir, Case& c) {
  if (!fs::exists(dir / "rest.obj")) return false;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("example_", 0) == 0 && entry.path().extension() == ".obj") files.push_back(entry.path());
  }
  if (files.empty()) return false;
  std::sort(files.begin(), files.end());
  c.name = "sample " + dir.filename().string();
  for (const PaperRow& row : kPaper) {
    std::string lower = row.name;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    if (dir.filename().string() == lower) c.paper = &row;
  }
  c.rest = meshik_bench::read_obj((dir / "rest.obj").string());
  for (const auto& f : files) c.examples.push_back(meshik_bench::read_obj(f.string()).vertices);
  if (c.examples.size() >= 3) {
    c.held_out = c.examples.back();
    c.examples.pop_back();
    c.note = c.name + ": targets from held-out " + files.back().filename().string();
  } else {
    c.held_out.assign(c.rest.vertices.size(), 0.0);
    for (const auto& e : c.examples)
      for (size_t i = 0; i < e.size(); ++i) c.held_out[i] += e[i] / c.examples.size();
    c.note = c.name + ": targets from the mean of the examples";
  }
  return true;
}

std::string with_commas(int value) {
  std::string digits = std::to_string(value), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// Paper seconds / ours (ms), or "-" when a figure is missing or zero.
std::string speedup(double paper_s, double ours_ms) {
  if (paper_s <= 0 || ours_ms <= 0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.0fx", paper_s * 1000.0 / ours_ms);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  std::string samples = "sample_meshes", data = "../shared/data", only;
  int repeats = 5;
  meshik::FeaturePrecision precision = meshik::FeaturePrecision::kSingle;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--samples") samples = argv[i + 1];
    else if (key == "--data") data = argv[i + 1];
    else if (key == "--repeats") repeats = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--only") only = argv[i + 1];
    else if (key == "--precision" && std::string(argv[i + 1]) == "double") precision = meshik::FeaturePrecision::kDouble;
    else if (key == "--precision" && std::string(argv[i + 1]) == "single") precision = meshik::FeaturePrecision::kSingle;
    else std::fprintf(stderr, "ignoring unknown option %s\n", key.c_str());
  }
  std::vector<Case> cases;
  if (fs::is_directory(samples)) {
    std::vector<fs::path> dirs;
    for (const auto& entry : fs::directory_iterator(samples))
      if (entry.is_directory()) dirs.push_back(entry.path());
    std::sort(dirs.begin(), dirs.end());
    for (const auto& dir : dirs) {
      Case c;
      if (load_sample_case(dir, c)) cases.push_back(std::move(c));
    }
  } else {
    std::printf("(no sample meshes at %s)\n", samples.c_str());
  }
  // lion-poses has 9 poses: 8 are examples and one is held out (the paper used 10 examples).
  const struct {
    const char* folder;
    int paper_row;
    std::vector<int> examples;
    int held_out;
  } data_sets[] = {{"lion-poses", 2, {1, 2, 3, 4, 5, 6, 7, 8}, 9},
                   {"horse-poses", 3, {1, 2, 3, 4}, 5},
                   {"elephant-poses", 4, {1, 2, 3, 4}, 5}};
  for (const auto& d : data_sets) {
    Case c;
    if (load_data_case(data, d.folder, &kPaper[d.paper_row], d.examples, d.held_out, c))
      cases.push_back(std::move(c));
  }

  const unsigned cores = std::thread::hardware_concurrency();
  std::printf("\nMeshIK vs the paper (Sumner et al. 2005, 3.4 GHz Pentium 4), nonlinear feature space,\n"
              "16 handles; ours: median of %d runs, on 1 thread and (nT columns) on all %u cores, alternately;\n"
              "features stored in %s precision. Paper figures in seconds, ours in ms.\n\n",
              repeats, cores, precision == meshik::FeaturePrecision::kSingle ? "single" : "double");
  std::printf("%-16s %7s %7s %3s | %8s %8s %8s | %9s %9s %9s %5s | %7s %7s %7s | %9s %9s %9s %6s | %9s %9s %8s\n",
              "Mesh", "Verts", "Tris", "Ex", "Factor s", "Solve s", "Total s", "Factor ms", "Solve ms", "Total ms",
              "Iter", "xFactor", "xSolve", "xTotal", "Factor nT", "Solve nT", "Total nT", "1T/nT", "Precomp",
              "Kept4th", "RMS err");
  std::vector<std::string> floors;
  for (const Case& c : cases) {
    if (!only.empty() && c.name.find(only) == std::string::npos) continue;
    const Timing t = time_case(c, repeats, precision);
    auto floor_line = [&](const char* what, double ms, double limit) {
      char line[160];
      std::snprintf(line, sizeof line, "%s %s %.2f ms (floor %.0f ms): %s", c.name.c_str(), what, ms, limit,
                    ms <= limit ? "met" : "MISSED");
      floors.push_back(line);
    };
    const double thread_speedup = t.pose_ms / t.threaded_pose_ms;
    if (c.name == "Elephant") {
      floor_line("factor (1 thread)", t.factor_ms, 60);
      floor_line("Gauss-Newton iteration (all cores)", t.threaded_iteration_ms, 10);
      floor_line("whole pose (all cores)", t.threaded_pose_ms, 30);
      char line[160];
      std::snprintf(line, sizeof line, "Elephant whole pose, 1 thread / all cores: %.2fx (floor 1.5x): %s",
                    thread_speedup, thread_speedup >= 1.5 ? "met" : "MISSED");
      floors.push_back(line);
    }
    if (c.name == "Horse") floor_line("whole pose (all cores)", t.threaded_pose_ms, 5);
    const PaperRow* p = c.paper;
    char paper_cols[64] = "       -        -        -";
    if (p) std::snprintf(paper_cols, sizeof paper_cols, "%8.3f %8.3f %8.3f", p->factor, p->solve, p->total);
    std::printf("%-16s %7s %7s %3zu | %s | %9.2f %9.2f %9.2f %5d | %7s %7s %7s | %9.2f %9.2f %9.2f %5.2fx | "
                "%9.1f %9.2f %8.5f\n",
                c.name.c_str(), with_commas(c.rest.num_vertices()).c_str(),
                with_commas(c.rest.num_triangles()).c_str(), c.examples.size(), paper_cols, t.factor_ms,
                t.iteration_ms, t.pose_ms, t.iterations, p ? speedup(p->factor, t.factor_ms).c_str() : "-",
                p ? speedup(p->solve, t.iteration_ms).c_str() : "-", p ? speedup(p->total, t.pose_ms).c_str() : "-",
                t.threaded_factor_ms, t.threaded_iteration_ms, t.threaded_pose_ms, thread_speedup, t.precompute_ms, t.kept_factor_ms, t.pose_error);
    std::fflush(stdout);
  }
  std::printf("\nPaper rows: Bar 132/260/2, Flag 516/932/14, Lion 5,000/9,996/10, Horse 8,425/16,846/4, "
              "Elephant 42,321/84,638/4.\n"
              "xFactor/xSolve/xTotal: paper time / our time (1 thread). nT: the same on all cores; 1T/nT: the\n"
              "whole pose's speed-up. Precomp: ExampleSet (features of all examples,\n"
              "the analysis of the mesh's system).\n"
              "Kept4th: our factorization of G'^T G' with the fourth vertices kept as unknowns and its own\n"
              "ordering (ms), the in-run comparison for Factor. RMS err: RMS vertex distance to the held-out pose / bbox diagonal.\n");
  for (const Case& c : cases) std::printf("  %s\n", c.note.c_str());
  if (!floors.empty()) std::printf("\nFloors (2-core machine):\n");
  for (const std::string& line : floors) std::printf("  %s\n", line.c_str());
  return 0;
}
