// The tool's "Mirror" option: each new handle gets a partner at the vertex nearest its mirror
// image, and every move and turn of a group is mirrored onto its partners. The plane goes through
// the rest mesh's centre, or through a vertex the user clicks (the click after choosing it).
#include "drag_tool.h"

#include "bounding_box.h"

#include <meshlab/glarea.h>

#include <algorithm>

namespace meshik::edit {
namespace {

constexpr double kMirrorTolerance = 0.01;  // of the rest mesh's bounding-box diagonal
const char* const kAxes = "XYZ";

}  // namespace

std::optional<MirrorPlane> DragTool::mirrorPlane() const {
  const int axis = panel_ ? panel_->mirrorAxis() : -1;
  if (axis < 0) return std::nullopt;
  if (!panel_->mirrorThroughPickedVertex()) return MirrorPlane::throughCentre(rest_positions_, axis);
  if (picked_mirror_plane_ && picked_mirror_plane_->axis == axis) return picked_mirror_plane_;
  return std::nullopt;
}

void DragTool::mirrorModeChanged() {
  picked_mirror_plane_.reset();
  if (area_) area_->update();  // the help line says whether a click picks the plane
}

bool DragTool::pickMirrorPlane(int vertex) {
  const int axis = panel_ ? panel_->mirrorAxis() : -1;
  if (axis < 0 || !panel_->mirrorThroughPickedVertex() || mirrorPlane()) return false;
  picked_mirror_plane_ = MirrorPlane::throughPoint(&rest_positions_[3 * static_cast<size_t>(vertex)], axis);
  log(QStringLiteral("mirror plane %1 = %2, through vertex %3")
          .arg(QChar(kAxes[axis]).toLower())
          .arg(picked_mirror_plane_->offset, 0, 'g', 9)
          .arg(vertex));
  if (area_) area_->update();
  return true;
}

void DragTool::addMirrorPartner() {
  const std::optional<MirrorPlane> plane = mirrorPlane();
  if (!plane || handles_.empty()) return;
  const int vertex = handles_.back();
  const double tolerance = kMirrorTolerance * boundingBox(rest_positions_.data(), rest_positions_.size() / 3).diagonal();
  const int partner = mirrorPartner(rest_positions_, vertex, *plane, tolerance);
  if (partner < 0) {
    report(QStringLiteral("no mirror partner for vertex %1: no rest vertex within %2 of the diagonal of its image "
                          "across the %3 plane")
               .arg(vertex)
               .arg(kMirrorTolerance)
               .arg(kAxes[plane->axis]));
    return;
  }
  if (partner == vertex) {
    log(QStringLiteral("vertex %1 lies on the %2 plane: its own mirror").arg(vertex).arg(kAxes[plane->axis]));
    return;
  }
  const int newest = static_cast<int>(handles_.size()) - 1;
  const auto found = std::find(handles_.begin(), handles_.end(), partner);
  if (found == handles_.end()) {
    const int group = partnerGroup(handles_, groups_, mirrors_, newest);
    handles_.push_back(partner);
    groups_.push_back(group >= 0 ? group : newGroupNumber(groups_));
    mirrors_.push_back(vertex);
    targets_.insert(targets_.end(), &last_written_[3 * partner], &last_written_[3 * partner] + 3);
  } else {
    mirrors_[found - handles_.begin()] = vertex;
  }
  mirrors_[newest] = partner;
  log(QStringLiteral("vertex %1 mirrors vertex %2 across the %3 plane (group %4)")
          .arg(partner)
          .arg(vertex)
          .arg(kAxes[plane->axis])
          .arg(groups_[std::find(handles_.begin(), handles_.end(), partner) - handles_.begin()]));
}

void DragTool::mirrorActiveGroup() {
  const std::optional<MirrorPlane> plane = mirrorPlane();
  if (!plane) return;
  for (int h : groupMembers(groups_, active_group_)) {
    if (mirrors_[h] < 0) continue;
    const auto partner = std::find(handles_.begin(), handles_.end(), mirrors_[h]);
    if (partner == handles_.end() || groups_[partner - handles_.begin()] == active_group_) continue;
    plane->reflect(&targets_[3 * h], &targets_[3 * (partner - handles_.begin())]);
  }
}

}  // namespace meshik::edit
