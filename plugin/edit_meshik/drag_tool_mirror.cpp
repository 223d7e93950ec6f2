// The tool's "Mirror" option: each new handle gets a partner at the vertex nearest its mirror
// image, and every move and turn of a group is mirrored onto its partners.
#include "drag_tool.h"

#include "bounding_box.h"
#include "mirror_pairing.h"

#include <meshlab/glarea.h>

#include <algorithm>

namespace meshik::edit {
namespace {

constexpr double kMirrorTolerance = 0.01;  // of the rest mesh's bounding-box diagonal

}  // namespace

void DragTool::addMirrorPartner() {
  const int axis = panel_ ? panel_->mirrorAxis() : -1;
  if (axis < 0 || handles_.empty()) return;
  const MirrorPlane plane = MirrorPlane::throughCentre(rest_positions_, axis);
  const int vertex = handles_.back();
  const double tolerance = kMirrorTolerance * boundingBox(rest_positions_.data(), rest_positions_.size() / 3).diagonal();
  const int partner = mirrorPartner(rest_positions_, vertex, plane, tolerance);
  static const char* kAxes = "XYZ";
  if (partner < 0) {
    report(QStringLiteral("no mirror partner for vertex %1: no rest vertex within %2 of the diagonal of its image "
                          "across the %3 plane through the centre")
               .arg(vertex)
               .arg(kMirrorTolerance)
               .arg(kAxes[axis]));
    return;
  }
  if (partner == vertex) return;  // on the plane: its own mirror
  const auto found = std::find(handles_.begin(), handles_.end(), partner);
  if (found == handles_.end()) {
    handles_.push_back(partner);
    groups_.push_back(newGroupNumber(groups_));
    mirrors_.push_back(vertex);
    targets_.insert(targets_.end(), &last_written_[3 * partner], &last_written_[3 * partner] + 3);
  } else {
    mirrors_[found - handles_.begin()] = vertex;
  }
  mirrors_[std::find(handles_.begin(), handles_.end(), vertex) - handles_.begin()] = partner;
  log(QStringLiteral("vertex %1 mirrors vertex %2 across the %3 plane").arg(partner).arg(vertex).arg(kAxes[axis]));
}

void DragTool::mirrorActiveGroup() {
  const int axis = panel_ ? panel_->mirrorAxis() : -1;
  if (axis < 0) return;
  const MirrorPlane plane = MirrorPlane::throughCentre(rest_positions_, axis);
  for (int h : groupMembers(groups_, active_group_)) {
    if (mirrors_[h] < 0) continue;
    const auto partner = std::find(handles_.begin(), handles_.end(), mirrors_[h]);
    if (partner == handles_.end() || groups_[partner - handles_.begin()] == active_group_) continue;
    plane.reflect(&targets_[3 * h], &targets_[3 * (partner - handles_.begin())]);
  }
}

}  // namespace meshik::edit
