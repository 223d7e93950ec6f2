#include "keyframe_list.h"

#include <algorithm>
#include <cstdio>

namespace meshik::edit {

std::string KeyframeList::add(const std::string& name, const std::vector<int>& handles, const std::vector<int>& groups,
                              const std::vector<double>& targets) {
  if (handles.empty()) return "no handle: a frame holds the handles' targets";
  if (groups.size() != handles.size() || targets.size() != 3 * handles.size())
    return "the handles, their groups and targets differ in number";
  if (!frames_.empty() && (handles != handles_ || groups != groups_))
    return "the handles changed since frame " + names_.front() +
           ": every frame needs the same handles (clear the frames to start a new animation)";
  if (std::find(names_.begin(), names_.end(), name) != names_.end()) return "a frame is already named " + name;
  handles_ = handles;
  groups_ = groups;
  names_.push_back(name);
  frames_.push_back(targets);
  return {};
}

void KeyframeList::clear() {
  handles_.clear();
  groups_.clear();
  names_.clear();
  frames_.clear();
}

std::string KeyframeList::nextName() const {
  char name[16];
  std::snprintf(name, sizeof name, "%04d", count() + 1);
  return name;
}

namespace {

// The distinct group numbers of `groups`, in the order they first appear.
std::vector<int> groupOrder(const std::vector<int>& groups) {
  std::vector<int> order;
  for (int g : groups)
    if (std::find(order.begin(), order.end(), g) == order.end()) order.push_back(g);
  return order;
}

// The file's groups from handles (#H) and their group numbers (#H).
std::vector<DragGroup> fileGroups(const std::vector<int>& handles, const std::vector<int>& groups) {
  std::vector<DragGroup> out;
  for (int g : groupOrder(groups)) {
    DragGroup group{"g" + std::to_string(g), {}};
    for (size_t h = 0; h < handles.size(); ++h)
      if (groups[h] == g) group.vertices.push_back(handles[h]);
    out.push_back(std::move(group));
  }
  return out;
}

// One frame of the file: per group (in groupOrder) its handles' targets.
DragKeyframe fileFrame(const std::string& name, const std::vector<int>& groups, const std::vector<double>& targets) {
  DragKeyframe frame{name, {}};
  for (int g : groupOrder(groups)) {
    std::vector<double> group_targets;
    for (size_t h = 0; h < groups.size(); ++h)
      if (groups[h] == g) group_targets.insert(group_targets.end(), &targets[3 * h], &targets[3 * h] + 3);
    frame.targets.push_back(std::move(group_targets));
  }
  return frame;
}

}  // namespace

void KeyframeList::fill(DragFrames& file) const {
  file.groups = fileGroups(handles_, groups_);
  file.frames.clear();
  for (size_t f = 0; f < frames_.size(); ++f) file.frames.push_back(fileFrame(names_[f], groups_, frames_[f]));
}

void fillOneFrame(DragFrames& file, const std::string& name, const std::vector<int>& handles,
                  const std::vector<int>& groups, const std::vector<double>& targets) {
  file.groups = fileGroups(handles, groups);
  file.frames = {fileFrame(name, groups, targets)};
}

}  // namespace meshik::edit
