// The ExampleSet precompute phase by phase (validation, locality order, topology and frames, the
// examples' features with their rotation branches, the normal matrix, the ordering and symbolic
// analysis) on the horse and the elephant with 4 examples (--data, ../shared/data), on one
// thread and on all cores, built alternately in the same run (the machine is shared: load
// drifts). Prints the median of each phase and the all-cores / one-thread ratio.
//
// Usage: bench_example_set [--data DIR] [--repeats N] [--only NAME]
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "example_set_impl.h"
#include "meshik/meshik.h"
#include "obj_reader.h"

namespace {

namespace fs = std::filesystem;

// Median of values, 0 when there are none.
double median_or_zero(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Per thread setting: each phase's times over the repeats, phases in the order they ran.
struct PhaseSamples {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> times;
};

void add_sample(const meshik::PhaseTimes& phases, PhaseSamples& samples) {
  double total = 0;
  for (const auto& [name, ms] : phases) {
    if (samples.times.find(name) == samples.times.end()) samples.order.push_back(name);
    samples.times[name].push_back(ms);
    total += ms;
  }
  if (samples.times.find("total") == samples.times.end()) samples.order.push_back("total");
  samples.times["total"].push_back(total);
}

void bench_mesh(const std::string& name, const fs::path& folder, int repeats) {
  const meshik_bench::TriangleMesh rest = meshik_bench::read_obj((folder / "reference.obj").string());
  std::vector<std::vector<double>> examples;
  for (int k = 1; k <= 4; ++k) examples.push_back(meshik_bench::read_obj((folder / (std::to_string(k) + ".obj")).string()).vertices);
  std::vector<const double*> pointers;
  for (const auto& e : examples) pointers.push_back(e.data());
  const meshik::MeshView view{rest.vertices.data(), rest.num_vertices(), rest.triangles.data(), rest.num_triangles()};
  const int settings[2] = {1, 0};  // one thread, all cores
  PhaseSamples samples[2];
  meshik::ExampleSet warm_up(view, pointers);
  for (int r = 0; r < repeats; ++r)
    for (int s = 0; s < 2; ++s) {
      const meshik::ExampleSet set(view, pointers, {}, settings[s]);
      add_sample(set.impl().phase_times, samples[s]);
    }
  std::printf("\n%s: %d vertices, %d triangles, 4 examples; median of %d alternating runs (ms)\n", name.c_str(),
              rest.num_vertices(), rest.num_triangles(), repeats);
  std::printf("  %-34s %10s %10s %8s %14s\n", "phase", "1 thread", "all cores", "all/1", "ns/(tri*ex) 1t");
  // Phases of either setting, in the order they ran.
  std::vector<std::string> phases = samples[0].order;
  for (const std::string& phase : samples[1].order)
    if (std::find(phases.begin(), phases.end(), phase) == phases.end())
      phases.insert(phases.end() - 1, phase);  // before "total"
  for (const std::string& phase : phases) {
    const double one = median_or_zero(samples[0].times[phase]), all = median_or_zero(samples[1].times[phase]);
    std::printf("  %-34s %10.2f %10.2f %8.2f %14.0f\n", phase.c_str(), one, all, one > 0 ? all / one : 0.0,
                1e6 * one / (4.0 * rest.num_triangles()));
  }
  if (name == "elephant") {
    const double one = median_or_zero(samples[0].times["total"]);
    std::printf("  floor: elephant ExampleSet on one thread %.1f ms <= 100 ms: %s\n", one, one <= 100 ? "met" : "MISSED");
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", only;
  int repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--data") data = argv[i + 1];
    else if (key == "--repeats") repeats = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--only") only = argv[i + 1];
    else if (key != "--samples") std::fprintf(stderr, "ignoring unknown option %s\n", key.c_str());
  }
  std::printf("ExampleSet precompute by phase, one thread against all cores\n");
  for (const char* name : {"horse", "elephant"}) {
    if (!only.empty() && only != name) continue;
    const fs::path folder = fs::path(data) / (std::string(name) + "-poses");
    if (!fs::exists(folder / "reference.obj")) {
      std::printf("(skipping %s: %s not found)\n", name, (folder / "reference.obj").c_str());
      continue;
    }
    bench_mesh(name, folder, repeats);
  }
  return 0;
}
