// Where the time of one Gauss-Newton iteration goes, on 1 thread and on all cores (measured
// alternately in the same run): the horse and the elephant from --data (../shared/data), examples 1-4,
// 16 farthest-point handles, targets from pose 5, at the linear start's weights. Phases:
//   factor    = the handle set's system (assembly of K' and its numeric factorization; once per
//               handle set, never per iteration),
//   evaluate  = one evaluation with the Jacobian (what an iteration runs once), split into
//     forward   = the forward solve of its 3 (#E + 1) right-hand sides,
//     backward  = the backward solve of the 3 coordinates of x0,
//     rest      = evaluate - forward - backward: blend and scatter of the features, the outer
//                 products of the forward-solved rows, the pose and its residuals,
//   second    = the second-order term (one more pass over the triangles, once per step taken),
//   blend     = the blend of every batch of triangles alone (part of rest; always on one thread).
// An iteration is about evaluate + second; the whole pose adds the first evaluation.
// Each team runs with the examples' features stored in single precision (the library's default)
// and in double (the comparison), all four taking turns.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "example_set_impl.h"
#include "linear_start.h"
#include "obj_reader.h"
#include "paper_handles.h"
#include "pose_evaluation.h"
#include "pose_system.h"
#include "thread_count.h"

namespace {

namespace fs = std::filesystem;

double milliseconds_of(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Medians (ms) of `repeats` runs of work(v) for each v in 0 .. variants - 1, the variants taking
// turns so that all see the same load of the machine. Returns one median per variant.
std::vector<double> alternate_medians(int repeats, size_t variants, const std::function<void(size_t)>& work) {
  std::vector<std::vector<double>> times(variants);
  for (int r = 0; r < repeats; ++r)
    for (size_t v = 0; v < variants; ++v) times[v].push_back(milliseconds_of([&] { work(v); }));
  std::vector<double> medians;
  for (auto& list : times) {
    std::sort(list.begin(), list.end());
    medians.push_back(list[list.size() / 2]);
  }
  return medians;
}

// One way to run the phases: a team and the example set whose features are stored in a precision.
struct Variant {
  int team;
  const meshik::ExampleSet::Impl* set;
  const meshik::PoseSystem* system;
  const char* precision;
};

// One data set's phases (see the header), per team and feature precision.
void time_phases(const std::string& name, const fs::path& dir, int repeats, const std::vector<int>& teams) {
  const auto rest = meshik_bench::read_obj((dir / "reference.obj").string());
  std::vector<std::vector<double>> examples;
  std::vector<const double*> pointers;
  for (int k = 1; k <= 4; ++k) examples.push_back(meshik_bench::read_obj((dir / (std::to_string(k) + ".obj")).string()).vertices);
  for (const auto& e : examples) pointers.push_back(e.data());
  const std::vector<double> pose = meshik_bench::read_obj((dir / "5.obj").string()).vertices;
  const meshik::MeshView view{rest.vertices.data(), rest.num_vertices(), rest.triangles.data(), rest.num_triangles()};
  const meshik::ExampleSet single_set(view, pointers, {}, 0, meshik::FeaturePrecision::kSingle);
  const meshik::ExampleSet double_set(view, pointers, {}, 0, meshik::FeaturePrecision::kDouble);
  // Both sets have the same internal order (it depends on the rest mesh only).
  const meshik::ExampleSet::Impl& set = single_set.impl();
  const std::vector<int> user_handles = meshik_bench::farthest_point_handles(rest.vertices, 16);
  std::vector<int> handles;
  std::vector<double> targets;
  for (int v : user_handles) {
    handles.push_back(set.internal_of_vertex[v]);
    for (int c = 0; c < 3; ++c) targets.push_back(pose[3 * static_cast<size_t>(v) + c]);
  }
  const meshik::PoseSystem single_system(set, handles);
  const meshik::PoseSystem double_system(double_set.impl(), handles);
  std::vector<Variant> variants;
  for (int team : teams) {
    variants.push_back({team, &set, &single_system, "single"});
    variants.push_back({team, &double_set.impl(), &double_system, "double"});
  }

  const auto factor = alternate_medians(repeats, variants.size(), [&](size_t v) {
    meshik::PoseSystem(*variants[v].set, handles, {}, variants[v].team);
  });
  meshik::EvaluationBuffers buffers;
  const Eigen::VectorXd weights = meshik::LinearStart(set, single_system, buffers).weights(targets.data(), 0.0);
  meshik::PoseEvaluation at;
  const auto evaluate = alternate_medians(repeats, variants.size(), [&](size_t v) {
    meshik::PoseEvaluator(*variants[v].set, *variants[v].system, meshik::FeatureSpace::kNonlinear, 0.0,
                          targets.data(), buffers, variants[v].team)
        .evaluate(weights.data(), true, at);
  });
  std::vector<double> blend_out(meshik::blend_batch_size(set.num_examples));
  const auto blend = alternate_medians(repeats, variants.size(), [&](size_t v) {
    const meshik::ExampleFeatures& features = variants[v].set->features;
    for (int batch = 0; batch < features.num_batches; ++batch)
      meshik::blend_batch(features, meshik::FeatureSpace::kNonlinear, weights.data(), batch, blend_out.data());
  });
  std::vector<double> second_order;
  for (const Variant& variant : variants) {
    meshik::PoseEvaluator evaluator(*variant.set, *variant.system, meshik::FeatureSpace::kNonlinear, 0.0,
                                    targets.data(), buffers, variant.team);
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
      evaluator.evaluate(weights.data(), true, at);
      times.push_back(milliseconds_of([&] { evaluator.add_second_order(at); }));
    }
    std::sort(times.begin(), times.end());
    second_order.push_back(times[times.size() / 2]);
  }
  const int columns = 3 * (set.num_examples + 1);
  const int stride = meshik::PoseSystem::padded_width(columns);
  std::vector<double> x(static_cast<size_t>(single_system.num_rows()) * stride);
  for (size_t i = 0; i < x.size(); ++i) x[i] = 1.0 / (1.0 + static_cast<double>(i % 97));
  const std::vector<double> b = x;
  const auto forward = alternate_medians(repeats, variants.size(), [&](size_t v) {
    std::copy(b.begin(), b.end(), x.begin());
    variants[v].system->forward_solve(x.data(), stride, columns, variants[v].team);
  });
  const auto backward = alternate_medians(repeats, variants.size(), [&](size_t v) {
    std::copy(b.begin(), b.end(), x.begin());
    variants[v].system->backward_solve(x.data(), stride, 3, variants[v].team);
  });
  const auto copy = alternate_medians(repeats, variants.size(), [&](size_t) { std::copy(b.begin(), b.end(), x.begin()); });
  for (size_t v = 0; v < variants.size(); ++v) {
    const double forward_ms = forward[v] - copy[v], backward_ms = backward[v] - copy[v];
    std::printf("%-9s %5d %9s | %8.2f | %8.2f %8.2f %8.2f %8.2f | %8.2f | %9.2f | %8.2f\n", name.c_str(),
                variants[v].team, variants[v].precision, factor[v], evaluate[v], forward_ms, backward_ms,
                evaluate[v] - forward_ms - backward_ms, second_order[v], evaluate[v] + second_order[v], blend[v]);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data";
  int repeats = 9;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--data") data = argv[i + 1];
    else if (key == "--repeats") repeats = std::max(1, std::atoi(argv[i + 1]));
    else if (key != "--samples") std::fprintf(stderr, "ignoring unknown option %s\n", key.c_str());
  }
  const std::vector<int> teams = {1, meshik::thread_count(0)};
  std::printf("One Gauss-Newton iteration by phase (median of %d runs, ms), nonlinear space, 16 handles,\n"
              "on 1 thread and on all %d cores, features stored in single and in double precision, alternately:\n\n",
              repeats, teams[1]);
  std::printf("%-9s %5s %9s | %8s | %8s %8s %8s %8s | %8s | %9s | %8s\n", "Mesh", "Team", "features", "factor", "evaluate",
              "forward", "backward", "rest", "second", "iteration", "blend");
  for (const auto& [name, folder] : {std::pair<const char*, const char*>{"Horse", "horse-poses"},
                                     std::pair<const char*, const char*>{"Elephant", "elephant-poses"}}) {
    const fs::path dir = fs::path(data) / folder;
    if (!fs::exists(dir / "reference.obj")) {
      std::printf("(skipping %s: %s not found)\n", name, (dir / "reference.obj").c_str());
      continue;
    }
    time_phases(name, dir, repeats, teams);
  }
  return 0;
}
