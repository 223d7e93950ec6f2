// The tool's undo history (a QUndoStack of PoseStep), the commands that change the pose without a
// drag (reset, clear), and the keyframe list.
#include "drag_tool.h"

#include "pose_step.h"

#include <meshlab/glarea.h>

#include <set>

namespace meshik::edit {

std::shared_ptr<const PoseState> DragTool::captureState() const {
  auto state = std::make_shared<PoseState>();
  state->handles = handles_;
  state->groups = groups_;
  state->targets = targets_;
  state->mirrors = mirrors_;
  state->vertices = last_written_;
  state->weights = last_weights_;
  return state;
}

void DragTool::pushStep(std::shared_ptr<const PoseState> before, const QString& text) {
  history_.push(new PoseStep(this, text, std::move(before), captureState()));
  log(QStringLiteral("%1 (undo steps: %2)").arg(text).arg(history_.index()));
}

void DragTool::restoreState(const PoseState& state, const QString& what) {
  MeshModel* rest = restLayer();
  if (rest == nullptr || state.vertices.size() != 3 * rest->cm.vert.size()) return;
  if (worker_) {
    worker_->waitIdle();
    worker_->take();  // a pose solved for the state being left
  }
  handles_ = state.handles;
  groups_ = state.groups;
  targets_ = state.targets;
  mirrors_ = state.mirrors;
  last_weights_ = state.weights;
  inverted_.clear();
  next_start_weights_ = state.weights;  // the next solve starts from this pose's weights
  if (!groups_.empty() && groupMembers(groups_, active_group_).empty()) active_group_ = groups_.back();
  writePose(*rest, state.vertices, SurfaceNormals{});
  if (panel_) {
    panel_->showError(QString());
    panel_->showPose(last_weights_, 0, 0.0, 0);
  }
  showHandleCount();
  log(QStringLiteral("%1: %2 handles, the pose of that step").arg(what).arg(handles_.size()));
}

void DragTool::showHandleCount() {
  const std::set<int> groups(groups_.begin(), groups_.end());
  if (panel_) panel_->showHandles(static_cast<int>(handles_.size()), static_cast<int>(groups.size()));
  if (area_) area_->update();
}

void DragTool::resetPose() {
  MeshModel* rest = restLayer();
  if (rest == nullptr || drag_ || rotation_) return;
  finishPendingSolve();
  const std::shared_ptr<const PoseState> before = captureState();
  for (size_t h = 0; h < handles_.size(); ++h)
    for (int k = 0; k < 3; ++k) targets_[3 * h + k] = rest_positions_[3 * handles_[h] + k];
  writePose(*rest, rest_positions_, SurfaceNormals{});
  last_weights_.assign(last_weights_.size(), 0.0);
  inverted_.clear();
  if (panel_) panel_->showPose(last_weights_, 0, 0.0, 0);
  next_start_weights_ = std::vector<double>();  // the next solve starts afresh, not from the last pose's weights
  pushStep(before, QStringLiteral("reset the pose"));
}

void DragTool::clearHandles() {
  if (drag_ || rotation_ || handles_.empty()) return;
  finishPendingSolve();
  const std::shared_ptr<const PoseState> before = captureState();
  handles_.clear();
  groups_.clear();
  targets_.clear();
  mirrors_.clear();
  active_group_ = 0;
  showHandleCount();
  pushStep(before, QStringLiteral("cleared the handles"));
}

void DragTool::addKeyframe() {
  if (drag_ || rotation_) return;
  finishPendingSolve();
  const std::string name = keyframes_.nextName();
  const std::string refused = keyframes_.add(name, handles_, groups_, targets_);
  if (!refused.empty()) {
    report(QString::fromStdString("frame not added: " + refused));
    return;
  }
  if (panel_) {
    panel_->showError(QString());
    panel_->showKeyframes(keyframes_.count());
  }
  log(QStringLiteral("frame %1 added (%2 frames, %3 handles)")
          .arg(QString::fromStdString(name))
          .arg(keyframes_.count())
          .arg(handles_.size()));
}

void DragTool::clearKeyframes() {
  keyframes_.clear();
  if (panel_) panel_->showKeyframes(0);
  log(QStringLiteral("frames cleared"));
}

}  // namespace meshik::edit
