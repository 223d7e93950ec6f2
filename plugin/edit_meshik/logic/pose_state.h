// What one step of the tool's undo history restores: the handles, their groups and targets, and
// the pose in the layer with its weights. The tool's QUndoStack holds one pair (before, after) per
// drag, rotation, handle added or removed, reset and clear.
#pragma once

#include <vector>

namespace meshik::edit {

struct PoseState {
  std::vector<int> handles;      // #H vertex indices
  std::vector<int> groups;       // #H group numbers: handles with one number move and turn together
  std::vector<double> targets;   // #H by 3 row-major targets
  std::vector<int> mirrors;      // #H: the vertex of the handle mirroring this one ("Mirror"), or -1
  std::vector<double> vertices;  // #V by 3 row-major: the pose written into the layer
  std::vector<double> weights;   // #E weights of that pose (empty: the rest pose, solved cold next)
};

// The positions (into handles, ascending) of the handles whose group number is `group`.
std::vector<int> groupMembers(const std::vector<int>& groups, int group);

// A group number no handle has yet (one more than the largest; 1 for none).
int newGroupNumber(const std::vector<int>& groups);

}  // namespace meshik::edit
