// A real example set of ../shared/data for the benchmarks: a rest mesh, its examples and a held-out
// pose (the targets' source), optionally midpoint-subdivided together (bench_scaling's and
// bench_thread_scaling's 1.08M triangles: the horse subdivided 3 times).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "midpoint_subdivision.h"
#include "obj_reader.h"

namespace meshik_bench {

struct PoseSet {
  TriangleMesh rest;
  std::vector<std::vector<double>> examples;  // #E arrays of #V by 3
  std::vector<double> held_out;               // #V by 3
};

// folder: an example-set folder holding reference.obj and 1.obj .. 5.obj. Returns the rest mesh,
// examples 1-4 and pose 5 held out; an empty set (no vertices) when reference.obj is missing.
inline PoseSet read_pose_set(const std::filesystem::path& folder) {
  PoseSet set;
  if (!std::filesystem::exists(folder / "reference.obj")) return set;
  set.rest = read_obj((folder / "reference.obj").string());
  for (int k = 1; k <= 4; ++k) set.examples.push_back(read_obj((folder / (std::to_string(k) + ".obj")).string()).vertices);
  set.held_out = read_obj((folder / "5.obj").string()).vertices;
  return set;
}

// base subdivided `levels` times (each triangle into 4), its poses with it.
inline PoseSet subdivided(const PoseSet& base, int levels) {
  PoseSet set = base;
  for (int level = 0; level < levels; ++level) {
    const MidpointStep step = midpoint_step(set.rest.triangles, set.rest.num_vertices());
    set.rest.vertices = subdivided_positions(set.rest.vertices, step);
    set.rest.triangles = step.new_triangles;
    for (auto& e : set.examples) e = subdivided_positions(e, step);
    set.held_out = subdivided_positions(set.held_out, step);
  }
  return set;
}

}  // namespace meshik_bench
