// edit_meshik_write_frame: writes a one-frame constraint file with the edit tool's writer, for the
// test that reads it back with the pipeline's loader (tests/python/test_edit_meshik_constraints.py).
// Usage: edit_meshik_write_frame OUT REST EXAMPLE,EXAMPLE,... V,V,... X,Y,Z,X,Y,Z,... linear|nonlinear K ITERATIONS
// The handles are one group "drag", written as positions (the rest mesh is not read).
#include "constraint_frames_writer.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

// The comma-separated items of `text`.
std::vector<std::string> items(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 9) {
    std::fprintf(stderr, "usage: %s OUT REST EXAMPLES HANDLES TARGETS linear|nonlinear K ITERATIONS\n", argv[0]);
    return 2;
  }
  meshik::edit::DragFrames file;
  file.rest_path = argv[2];
  file.example_paths = items(argv[3]);
  meshik::edit::DragGroup group{"drag", {}};
  meshik::edit::DragKeyframe frame{"drag", {{}}};
  for (const std::string& v : items(argv[4])) group.vertices.push_back(std::stoi(v));
  for (const std::string& x : items(argv[5])) frame.targets[0].push_back(std::strtod(x.c_str(), nullptr));
  file.groups = {group};
  file.frames = {frame};
  file.linear_feature_space = std::string(argv[6]) == "linear";
  file.weight_regularization = std::strtod(argv[7], nullptr);
  file.max_iterations = std::atoi(argv[8]);
  try {
    meshik::edit::writeConstraintFrames(argv[1], file, nullptr, 0);
  } catch (const meshik::edit::ConstraintWriteError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
