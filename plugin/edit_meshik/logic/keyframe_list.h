// The frames "Add frame" collects: the handles' targets at each press, for one constraint file
// (an animation posed by dragging replays in `meshik pose` / `meshik batch`). Every frame has the
// handles and groups of the first one: a vertex that is free in one frame and held in another
// cannot be written as a frame of one file.
#pragma once

#include "constraint_frames_writer.h"

#include <string>
#include <vector>

namespace meshik::edit {

class KeyframeList {
 public:
  // Appends a frame named `name` (letters, digits, "._-"): handles (#H vertex indices), their
  // group numbers (#H) and targets (#H by 3). Returns "" when added, else why not (no handle,
  // other handles or groups than the first frame's, a name already used).
  std::string add(const std::string& name, const std::vector<int>& handles, const std::vector<int>& groups,
                  const std::vector<double>& targets);
  void clear();
  int count() const { return static_cast<int>(frames_.size()); }
  // The name "0001", "0002", ... that the next frame gets by default.
  std::string nextName() const;

  // The file's groups (one per group number, named "g<number>", its handles in their order) and
  // frames (each group's targets) into `file`.
  void fill(DragFrames& file) const;

 private:
  std::vector<int> handles_;
  std::vector<int> groups_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> frames_;  // per frame: #H by 3 targets
};

// The file's groups and one frame named `name` for the handles (#H), their group numbers (#H)
// and targets (#H by 3) of the moment, without a keyframe list.
void fillOneFrame(DragFrames& file, const std::string& name, const std::vector<int>& handles,
                  const std::vector<int>& groups, const std::vector<double>& targets);

}  // namespace meshik::edit
