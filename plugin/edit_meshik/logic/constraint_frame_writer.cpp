// writeConstraintFrame: the tool's handles as one frame of a constraint file, written through
// the constraint-file library (meshik::constraints::write_constraint_file), so the file the tool
// saves follows the same rules as every file the pipeline and the filter read.
#include "constraint_frame_writer.h"

#include "meshik/constraints/constraint_file.h"

#include <cstdint>

namespace meshik::edit {
namespace {

// What the library cannot know: the layers' files must exist on disk before they can be named.
void checkLayerFiles(const std::string& path, const DragFrame& frame) {
  if (path.empty()) throw ConstraintWriteError("constraint file: no file name given");
  if (frame.rest_path.empty()) throw ConstraintWriteError(path + ": the rest mesh has no file (save it first)");
  if (frame.example_paths.empty()) throw ConstraintWriteError(path + ": no example mesh");
  for (size_t i = 0; i < frame.example_paths.size(); ++i)
    if (frame.example_paths[i].empty())
      throw ConstraintWriteError(path + ": example " + std::to_string(i) + " has no file (save it first)");
  if (frame.handles.empty()) throw ConstraintWriteError(path + ": no handle");
}

}  // namespace

void writeConstraintFrame(const std::string& path, const DragFrame& frame) {
  checkLayerFiles(path, frame);
  constraints::GroupPositions group{frame.group_name,
                                    std::vector<std::int64_t>(frame.handles.begin(), frame.handles.end()),
                                    frame.targets};
  constraints::WrittenSettings settings;
  settings.feature_space = frame.linear_feature_space ? "linear" : "nonlinear";
  settings.weight_regularization = frame.weight_regularization;
  settings.max_iterations = frame.max_iterations;
  try {
    constraints::write_constraint_file(path, frame.rest_path, frame.example_paths, {group}, frame.frame_name,
                                       settings);
  } catch (const constraints::ConstraintError& error) {
    throw ConstraintWriteError(error.what());
  }
}

}  // namespace meshik::edit
