// The tool's "Mirror" option: each new handle gets a partner at the vertex nearest its mirror
// image, and every move and turn of a group is mirrored onto its partners. The plane is normal to
// X, Y or Z, or the view's vertical plane (taken from the view when the option is chosen); it goes
// through the rest mesh's centre, or through a vertex the user clicks (the click after choosing it).
#include "drag_tool.h"

#include "bounding_box.h"

#include <meshlab/glarea.h>

#include <algorithm>

namespace meshik::edit {
namespace {

constexpr double kMirrorTolerance = 0.01;  // of the rest mesh's bounding-box diagonal

// The normal of the plane chosen in `panel` (null or off: none): an axis, or `view_normal` for the
// view's vertical plane (none while the view is not known).
std::optional<Direction> chosenNormal(const DragDock* panel, const std::optional<Direction>& view_normal) {
  const int kind = panel ? panel->mirrorPlaneKind() : DragDock::kNoMirror;
  if (kind == DragDock::kNoMirror) return std::nullopt;
  if (kind == DragDock::kViewMirror) return view_normal;
  return axisNormal(kind);
}

// "x = 0.5" for a plane normal to an axis, else "(0.6, 0, 0.8) . p = 0.5".
QString planeEquation(const MirrorPlane& plane) {
  for (int axis = 0; axis < 3; ++axis)
    if (plane.normal == axisNormal(axis))
      return QStringLiteral("%1 = %2").arg(QChar("xyz"[axis])).arg(plane.offset, 0, 'g', 9);
  return QStringLiteral("(%1, %2, %3) . p = %4")
      .arg(plane.normal[0], 0, 'g', 9)
      .arg(plane.normal[1], 0, 'g', 9)
      .arg(plane.normal[2], 0, 'g', 9)
      .arg(plane.offset, 0, 'g', 9);
}

}  // namespace

std::optional<MirrorPlane> DragTool::mirrorPlane() const {
  const std::optional<Direction> normal = chosenNormal(panel_, view_mirror_normal_);
  if (!normal) return std::nullopt;
  if (!panel_->mirrorThroughPickedVertex()) return MirrorPlane::throughCentre(rest_positions_, *normal);
  return picked_mirror_plane_;
}

void DragTool::mirrorModeChanged() {
  picked_mirror_plane_.reset();
  view_mirror_normal_.reset();
  if (panel_ && panel_->mirrorPlaneKind() == DragDock::kViewMirror) {
    if (projection_) {
      view_mirror_normal_ = viewVerticalNormal(projection_->modelview());
      log(QStringLiteral("mirror plane normal (%1, %2, %3): the view's vertical plane, fixed until the option is "
                         "chosen again")
              .arg((*view_mirror_normal_)[0], 0, 'g', 9)
              .arg((*view_mirror_normal_)[1], 0, 'g', 9)
              .arg((*view_mirror_normal_)[2], 0, 'g', 9));
    } else {
      report("the view's vertical plane: the view is not drawn yet; choose the option again");
    }
  }
  if (area_) area_->update();  // the help line says whether a click picks the plane
}

bool DragTool::pickMirrorPlane(int vertex) {
  const std::optional<Direction> normal = chosenNormal(panel_, view_mirror_normal_);
  if (!normal || !panel_->mirrorThroughPickedVertex() || mirrorPlane()) return false;
  picked_mirror_plane_ = MirrorPlane::throughPoint(&rest_positions_[3 * static_cast<size_t>(vertex)], *normal);
  log(QStringLiteral("mirror plane %1, through vertex %2").arg(planeEquation(*picked_mirror_plane_)).arg(vertex));
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
               .arg(panel_->mirrorPlaneName()));
    return;
  }
  if (partner == vertex) {
    log(QStringLiteral("vertex %1 lies on the %2 plane: its own mirror").arg(vertex).arg(panel_->mirrorPlaneName()));
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
          .arg(panel_->mirrorPlaneName())
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
