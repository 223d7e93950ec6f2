// writeConstraintFrames: the tool's groups and keyframes as a constraint file, written through
// the constraint-file library (meshik::constraints::write_constraint_frames), so the file the
// tool saves follows the same rules as every file the pipeline and the filter read.
#include "constraint_frames_writer.h"

#include "meshik/constraints/constraint_file.h"
#include "meshik/meshik.h"
#include "bounding_box.h"
#include "rigid_fit.h"

#include <cstdint>

namespace meshik::edit {
namespace {

// What the library cannot know: the layers' files must exist on disk before they can be named,
// and the groups' vertices must be on the rest mesh.
void checkContent(const std::string& path, const DragFrames& frames, int num_vertices) {
  if (path.empty()) throw ConstraintWriteError("constraint file: no file name given");
  if (frames.rest_path.empty()) throw ConstraintWriteError(path + ": the rest mesh has no file (save it first)");
  if (frames.example_paths.empty()) throw ConstraintWriteError(path + ": no example mesh");
  for (size_t i = 0; i < frames.example_paths.size(); ++i)
    if (frames.example_paths[i].empty())
      throw ConstraintWriteError(path + ": example " + std::to_string(i) + " has no file (save it first)");
  if (frames.groups.empty()) throw ConstraintWriteError(path + ": no handle");
  if (frames.frames.empty()) throw ConstraintWriteError(path + ": no frame");
  for (const DragGroup& group : frames.groups)
    for (int v : group.vertices)
      if (v < 0 || (num_vertices >= 0 && v >= num_vertices))
        throw ConstraintWriteError(path + ": handle group \"" + group.name + "\": vertex " + std::to_string(v) +
                                   " is not on the rest mesh (" + std::to_string(num_vertices) + " vertices)");
}

// The target of `group` in a frame: the rigid motion of its rest positions that `targets` are
// (within `tolerance`) when it has two vertices or more and the rest is known, else the positions.
constraints::GroupTarget groupTarget(const DragGroup& group, const std::vector<double>& targets,
                                     const double* rest_vertices, double tolerance) {
  constraints::GroupTarget target;
  target.group = group.name;
  target.positions = targets;
  if (!rest_vertices || group.vertices.size() < 2 || targets.size() != 3 * group.vertices.size()) return target;
  std::vector<double> rest;
  for (int v : group.vertices) rest.insert(rest.end(), rest_vertices + 3 * v, rest_vertices + 3 * v + 3);
  if (const auto motion = fitRigidMotion(rest.data(), targets.data(), group.vertices.size(), tolerance)) {
    target.rigid = true;
    target.positions.clear();
    target.rotation = motion->rotation;
    target.translation = motion->translation;
    target.center = motion->center;
  }
  return target;
}

}  // namespace

void writeConstraintFrames(const std::string& path, const DragFrames& frames, const double* rest_vertices,
                           int num_vertices) {
  checkContent(path, frames, rest_vertices ? num_vertices : -1);
  const double tolerance =
      rest_vertices ? 1e-9 * boundingBox(rest_vertices, static_cast<size_t>(num_vertices)).diagonal() : 0.0;
  std::vector<constraints::HandleGroup> groups;
  for (const DragGroup& group : frames.groups)
    groups.push_back({group.name, std::vector<std::int64_t>(group.vertices.begin(), group.vertices.end()),
                      std::nullopt, 0.0});
  std::vector<constraints::Frame> written;
  for (const DragKeyframe& frame : frames.frames) {
    constraints::Frame out{frame.name, {}};
    for (size_t g = 0; g < frames.groups.size() && g < frame.targets.size(); ++g)
      if (!frame.targets[g].empty())
        out.targets.push_back(groupTarget(frames.groups[g], frame.targets[g], rest_vertices, tolerance));
    written.push_back(std::move(out));
  }
  constraints::WrittenSettings settings;
  settings.feature_space = frames.linear_feature_space ? "linear" : "nonlinear";
  settings.weight_regularization = frames.weight_regularization;
  settings.blend = frames.free_blend ? "free" : "affine";
  if (frames.regions != 1) {
    settings.regions = frames.regions == kAutomaticRegions ? -1 : frames.regions;
    settings.region_smoothness = frames.region_smoothness;
  }
  if (frames.handle_stiffness != 0.0) settings.handle_stiffness = frames.handle_stiffness;
  settings.max_iterations = frames.max_iterations;
  try {
    constraints::write_constraint_frames(path, frames.rest_path, frames.example_paths, groups, written, settings);
  } catch (const constraints::ConstraintError& error) {
    throw ConstraintWriteError(error.what());
  }
}

}  // namespace meshik::edit
