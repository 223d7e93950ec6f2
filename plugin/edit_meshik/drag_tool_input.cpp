// The tool's mouse and keys: clicks add or remove handles, a rectangle drawn from an empty spot
// makes a group of the visible vertices inside it, a drag moves a group, R turns one
// (X/Y/Z lock the axis, typed degrees, Return applies, Backspace or Esc cancels, as in MeshLab's
// edit_manipulators), Esc cancels a drag, Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y step through the
// history, a middle or alt drag and the wheel move the view (MeshLab's own trackball).
#include "drag_tool.h"

#include "../layer_arrays.h"
#include "bounding_box.h"
#include "pose_step.h"
#include "vertex_picking.h"

#include <meshlab/glarea.h>

#include <QApplication>
#include <QCursor>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>

namespace meshik::edit {
namespace {

constexpr double kHandleRadiusPixels = 10.0;  // a press this close to a handle's marker grabs it
constexpr double kPickRadiusPixels = 12.0;    // a click this close to a vertex picks it

// Whether `event` is one of the history keys: Ctrl+Z (undo), Ctrl+Shift+Z or Ctrl+Y (redo).
bool isHistoryKey(const QKeyEvent* event) {
  return (event->modifiers() & Qt::ControlModifier) && (event->key() == Qt::Key_Z || event->key() == Qt::Key_Y);
}

// Whether `key` (without modifiers) is one of the tool's command keys.
bool isToolKey(int key) {
  return key == Qt::Key_R || key == Qt::Key_S || key == Qt::Key_P || key == Qt::Key_F || key == Qt::Key_N ||
         key == Qt::Key_M;
}

// Whether a mouse press means view navigation: the middle button, or the left one with Alt.
bool isNavigationPress(const QMouseEvent* event) {
  return event->button() == Qt::MiddleButton ||
         (event->button() == Qt::LeftButton && (event->modifiers() & Qt::AltModifier));
}

}  // namespace

std::pair<double, double> DragTool::glPosition(const QMouseEvent* event) const {
  const double scale = area_ ? area_->devicePixelRatioF() : 1.0;
  const double height = area_ ? area_->height() : 0.0;
  return {event->x() * scale, (height - event->y()) * scale};
}

std::pair<double, double> DragTool::cursorGlPosition() const {
  if (area_ == nullptr) return {0.0, 0.0};
  const QPoint local = area_->mapFromGlobal(QCursor::pos());
  const double scale = area_->devicePixelRatioF();
  return {local.x() * scale, (area_->height() - local.y()) * scale};
}

bool DragTool::eventFilter(QObject* watched, QEvent* event) {
  if (watched == area_ && event->type() == QEvent::ShortcutOverride) {
    const auto* key = static_cast<QKeyEvent*>(event);
    const bool busy = drag_ || rotation_;
    if (isHistoryKey(key) || (busy && key->key() == Qt::Key_Escape) ||
        (key->modifiers() == Qt::NoModifier && (rotation_ || isToolKey(key->key())))) {
      event->accept();  // the key goes to keyPressEvent, not to a MeshLab shortcut (Esc: "Not editing")
      return true;
    }
  }
  if (watched == area_ && event->type() == QEvent::MouseMove && !navigating_ && (drag_ || rotation_dragging_)) {
    // A move of a drag or turn is taken here, before GLArea, which would repaint the view for it:
    // the view is repainted once the new pose is in the layer (refreshBuffers), so the GUI thread
    // is not busy painting an unchanged pose when the worker's result arrives.
    moveHandles(static_cast<QMouseEvent*>(event));
    return true;
  }
  return QObject::eventFilter(watched, event);
}

void DragTool::navigate(QEvent* event) {
  if (area_ == nullptr) return;
  const bool was = area_->suspendedEditor;
  area_->suspendedEditor = true;  // GLArea then drives its trackball with the event
  if (event->type() == QEvent::Wheel) {
    QApplication::sendEvent(area_, event);
  } else {
    auto* mouse = static_cast<QMouseEvent*>(event);
    QMouseEvent plain(mouse->type(), mouse->localPos(), mouse->windowPos(), mouse->screenPos(), mouse->button(),
                      mouse->buttons(),
                      mouse->modifiers() & ~Qt::AltModifier);  // alt+left turns the view like a plain left drag
    QApplication::sendEvent(area_, &plain);
  }
  area_->suspendedEditor = was;
}

void DragTool::mousePressEvent(QMouseEvent* event, MeshModel&, GLArea* area) {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  if (isNavigationPress(event) && !drag_ && !rotation_dragging_) {
    navigating_ = true;
    navigate(event);
    return;
  }
  if (event->button() != Qt::LeftButton) return;
  const auto [x, y] = glPosition(event);
  if (rotation_ && projection_) {  // R was pressed: this drag turns (the group under the press, if any)
    const int grabbed = pickHandle(*projection_, targets_, x, y, kHandleRadiusPixels);
    if (grabbed >= 0 && groups_[grabbed] != active_group_) {
      restoreState(*step_before_, QStringLiteral("turn moved to another group"));
      active_group_ = groups_[grabbed];
    }
    rotation_.emplace(*projection_, step_before_->targets, groupMembers(groups_, active_group_), x, y);
    typed_degrees_.clear();
    rotation_dragging_ = true;
    area->update();
    return;
  }
  const bool remove = event->modifiers() & Qt::ShiftModifier;
  if (!remove && projection_ && worker_) {
    const int grabbed = pickHandle(*projection_, targets_, x, y, kHandleRadiusPixels);
    if (grabbed >= 0) {
      active_group_ = groups_[grabbed];
      step_before_ = captureState();
      drag_.emplace(*projection_, targets_, grabbed, groupMembers(groups_, active_group_), x, y);
      last_move_screen_ = event->globalPos();
      timings_.clear();
      drag_start_counts_ = worker_->counts();
      area->update();
      return;
    }
  }
  pressed_ = Click{x, y, remove, static_cast<bool>(event->modifiers() & Qt::ControlModifier)};
}

void DragTool::mouseMoveEvent(QMouseEvent* event, MeshModel&, GLArea* area) {
  if (navigating_) {
    navigate(event);
    return;
  }
  if (drag_ || rotation_dragging_) {
    moveHandles(event);
    return;
  }
  const auto [x, y] = glPosition(event);
  if (pressed_ && (rectangle_ || std::hypot(x - pressed_->x, y - pressed_->y) >= 5.0)) {
    rectangle_ = Rectangle{pressed_->x, pressed_->y, x, y};
    area->update();
  }
}

void DragTool::moveHandles(const QMouseEvent* event) {
  const Clock::time_point now = Clock::now();
  const auto [x, y] = glPosition(event);
  last_move_screen_ = event->globalPos();
  if (rotation_ && rotation_dragging_) {
    if (!typed_degrees_.isEmpty()) return;  // typed degrees rule the turn
    targets_ = rotation_->targetsTurnedBy(rotation_->dialDegrees(x, y));
  } else if (drag_) {
    targets_ = drag_->targetsAt(x, y);
  } else {
    return;
  }
  mirrorActiveGroup();
  postSolve(true, now);  // one warm-started Gauss-Newton step per move; the release converges
}

void DragTool::mouseReleaseEvent(QMouseEvent* event, MeshModel&, GLArea* area) {
  if (navigating_) {
    navigate(event);
    navigating_ = event->buttons() != Qt::NoButton;
    return;
  }
  if (rotation_ && rotation_dragging_) {
    applyRotation();
    return;
  }
  if (pressed_) {  // a click, or the end of a rectangle: handled in decorate, where the depth buffer is
    if (rectangle_) pending_rectangle_ = rectangle_;
    else pending_click_ = pressed_;
    pressed_.reset();
    rectangle_.reset();
    area->update();
    return;
  }
  if (!drag_ || !worker_) return;
  finishPendingSolve();
  const SolveWorker::Counts counts = worker_->counts();
  const int group = active_group_;
  drag_.reset();
  convergeNow();
  const QString summary =
      QStringLiteral("%1 moves, %2 solves (%3 coalesced, %4 superseded), the last move at screen %5 %6; latency "
                     "median %7 ms, max %8 ms; solve median %9 ms, overhead median %10 ms (waiting for the GUI "
                     "thread %11 ms, writing the layer and GL buffers %12 ms, of it MeshLab's GL buffers %13 ms; "
                     "renderer backlog %14 ms)")
          .arg(counts.moves - drag_start_counts_.moves)
          .arg(counts.solves - drag_start_counts_.solves)
          .arg(counts.coalesced - drag_start_counts_.coalesced)
          .arg(counts.superseded - drag_start_counts_.superseded)
          .arg(last_move_screen_.x())
          .arg(last_move_screen_.y())
          .arg(timings_.latency.median(), 0, 'f', 1)
          .arg(timings_.latency.max(), 0, 'f', 1)
          .arg(timings_.solve.median(), 0, 'f', 1)
          .arg(timings_.overhead.median(), 0, 'f', 2)
          .arg(timings_.waiting.median(), 0, 'f', 2)
          .arg(timings_.writing.median(), 0, 'f', 2)
          .arg(timings_.buffers.median(), 0, 'f', 2)
          .arg(timings_.backlog.median(), 0, 'f', 2);
  log(summary);
  if (panel_) panel_->showLatency(summary);
  pushStep(std::move(step_before_), QStringLiteral("drag group %1").arg(group));
  area->update();
}

void DragTool::wheelEvent(QWheelEvent* event, MeshModel&, GLArea*) { navigate(event); }

void DragTool::cancelDrag() {
  if (!drag_) return;
  drag_.reset();
  restoreState(*step_before_, QStringLiteral("drag cancelled"));
  step_before_.reset();
}

void DragTool::beginRotation() {
  if (rotation_ || drag_ || !projection_ || !worker_) return;
  if (groupMembers(groups_, active_group_).empty()) {
    report(QStringLiteral("no handle group to turn: click a vertex first"));
    return;
  }
  finishPendingSolve();
  step_before_ = captureState();
  const auto [x, y] = cursorGlPosition();
  const int hovered = pickHandle(*projection_, targets_, x, y, kHandleRadiusPixels);
  if (hovered >= 0) active_group_ = groups_[hovered];  // R over a handle turns its group
  rotation_.emplace(*projection_, targets_, groupMembers(groups_, active_group_), x, y);
  typed_degrees_.clear();
  rotation_dragging_ = false;
  timings_.clear();
  log(QStringLiteral("turning group %1: drag to turn, X/Y/Z axis, type degrees, Return applies, Backspace cancels")
          .arg(active_group_));
  if (area_) area_->update();
}

void DragTool::updateRotation() {
  if (!rotation_) return;
  if (!typed_degrees_.isEmpty()) targets_ = rotation_->targetsTurnedBy(typed_degrees_.toDouble());
  mirrorActiveGroup();
  postSolve(true, Clock::now());
  if (area_) area_->update();
}

void DragTool::applyRotation() {
  if (!rotation_) return;
  if (!typed_degrees_.isEmpty()) targets_ = rotation_->targetsTurnedBy(typed_degrees_.toDouble());
  mirrorActiveGroup();
  static const char* kAxisNames[] = {"the view axis", "X", "Y", "Z"};
  const QString axis = kAxisNames[static_cast<int>(rotation_->axis())];
  rotation_.reset();
  rotation_dragging_ = false;
  typed_degrees_.clear();
  convergeNow();
  pushStep(std::move(step_before_), QStringLiteral("turn group %1 about %2").arg(active_group_).arg(axis));
  if (area_) area_->update();
}

void DragTool::cancelRotation() {
  if (!rotation_) return;
  rotation_.reset();
  rotation_dragging_ = false;
  typed_degrees_.clear();
  restoreState(*step_before_, QStringLiteral("turn cancelled"));
  step_before_.reset();
}

bool DragTool::handleRotationKey(QKeyEvent* event) {
  const int key = event->key();
  if (key == Qt::Key_X || key == Qt::Key_Y || key == Qt::Key_Z) {
    const RotationAxis axis = key == Qt::Key_X ? RotationAxis::kX : key == Qt::Key_Y ? RotationAxis::kY : RotationAxis::kZ;
    rotation_->setAxis(rotation_->axis() == axis ? RotationAxis::kView : axis);  // again: back to the view axis
    if (typed_degrees_.isEmpty()) targets_ = rotation_->targetsTurnedBy(0.0);
    updateRotation();
  } else if ((key >= Qt::Key_0 && key <= Qt::Key_9) || key == Qt::Key_Period ||
             (key == Qt::Key_Minus && typed_degrees_.isEmpty())) {
    typed_degrees_ += event->text();
    updateRotation();
  } else if (key == Qt::Key_Return || key == Qt::Key_Enter) {
    applyRotation();
  } else if (key == Qt::Key_Backspace || key == Qt::Key_Escape) {
    cancelRotation();
  } else {
    return false;
  }
  return true;
}

void DragTool::keyPressEvent(QKeyEvent* event, MeshModel&, GLArea*) {
  if (isHistoryKey(event)) {
    if (drag_ || rotation_) return;
    finishPendingSolve();
    const bool redo = event->key() == Qt::Key_Y || (event->modifiers() & Qt::ShiftModifier);
    if (redo ? history_.canRedo() : history_.canUndo()) {
      if (redo) history_.redo();
      else history_.undo();
    } else {
      log(redo ? QStringLiteral("nothing to redo") : QStringLiteral("nothing to undo"));
    }
    event->accept();
    return;
  }
  if (rotation_) {
    if (handleRotationKey(event)) event->accept();
    return;
  }
  if (drag_) {
    if (event->key() == Qt::Key_Escape) {
      cancelDrag();
      event->accept();
    }
    return;
  }
  switch (event->key()) {
    case Qt::Key_R: beginRotation(); break;
    case Qt::Key_S: saveConstraintFile(); break;
    case Qt::Key_P: savePose(); break;
    case Qt::Key_F: addKeyframe(); break;
    case Qt::Key_N: poseToNewLayer(); break;
    case Qt::Key_M:
      if (panel_) log(QStringLiteral("mirror: %1").arg(panel_->cycleMirror()));
      break;
    default: return;
  }
  event->accept();
}

void DragTool::handleClick(const Click& click, MeshModel& layer) {
  int handle = pickHandle(*projection_, targets_, click.x, click.y, kHandleRadiusPixels);
  const std::shared_ptr<const PoseState> before = captureState();
  if (handle < 0 || !click.remove) {
    float depth = 1.0f;
    glReadPixels(static_cast<GLint>(click.x), static_cast<GLint>(click.y), 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
    const int vertex = pickVertex(*projection_, last_written_, click.x, click.y, depth, kPickRadiusPixels);
    if (vertex < 0 || (!click.remove && pickMirrorPlane(vertex))) return;
    const auto found = std::find(handles_.begin(), handles_.end(), vertex);
    if (click.remove) {
      if (found == handles_.end()) return;
      handle = static_cast<int>(found - handles_.begin());
    } else {
      if (found != handles_.end()) return;
      const bool join = click.add_to_group && !groupMembers(groups_, active_group_).empty();
      active_group_ = join ? active_group_ : newGroupNumber(groups_);
      handles_.push_back(vertex);
      groups_.push_back(active_group_);
      mirrors_.push_back(-1);
      for (int k = 0; k < 3; ++k) targets_.push_back(static_cast<double>(layer.cm.vert[vertex].cP()[k]));
    }
  }
  if (click.remove) {
    for (int& m : mirrors_)
      if (m == handles_[handle]) m = -1;
    handles_.erase(handles_.begin() + handle);
    groups_.erase(groups_.begin() + handle);
    mirrors_.erase(mirrors_.begin() + handle);
    targets_.erase(targets_.begin() + 3 * handle, targets_.begin() + 3 * handle + 3);
  }
  QString where;
  if (!click.remove) {  // where the new handle's marker is on the screen (for scripts driving the GUI)
    const WindowPoint w = projection_->project(&targets_[targets_.size() - 3]);
    const double scale = area_->devicePixelRatioF();
    const QPoint screen = area_->mapToGlobal(QPoint(static_cast<int>(std::lround(w.x / scale)),
                                                    static_cast<int>(std::lround(area_->height() - w.y / scale))));
    where = QStringLiteral(", the new one vertex %1 (group %4) at screen %2 %3")
                .arg(handles_.back())
                .arg(screen.x())
                .arg(screen.y())
                .arg(groups_.back());
  }
  log(QStringLiteral("%1 handles%2").arg(handles_.size()).arg(where));
  if (!click.remove) addMirrorPartner();
  showHandleCount();
  // No solve here: a new handle holds its vertex where it is, so the pose does not jump; the next
  // move solves with the new handle set (and refactors then).
  history_.push(new PoseStep(this, click.remove ? QStringLiteral("remove a handle") : QStringLiteral("add a handle"),
                             before, captureState()));
}

void DragTool::handleRectangle(const Rectangle& rectangle) {
  const int left = static_cast<int>(std::floor(std::min(rectangle.x0, rectangle.x1)));
  const int bottom = static_cast<int>(std::floor(std::min(rectangle.y0, rectangle.y1)));
  const int width = static_cast<int>(std::ceil(std::abs(rectangle.x1 - rectangle.x0))) + 1;
  const int height = static_cast<int>(std::ceil(std::abs(rectangle.y1 - rectangle.y0))) + 1;
  std::vector<float> depths(static_cast<size_t>(width) * height, 1.0f);
  glReadPixels(left, bottom, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depths.data());
  const auto depth_at = [&](int x, int y) -> double {
    if (x < left || y < bottom || x >= left + width || y >= bottom + height) return 1.0;
    return depths[static_cast<size_t>(y - bottom) * width + (x - left)];
  };
  const double tolerance = 0.01 * boundingBox(last_written_.data(), last_written_.size() / 3).diagonal();
  const std::vector<int> inside = pickVerticesInRectangle(*projection_, last_written_, rectangle.x0, rectangle.y0,
                                                          rectangle.x1, rectangle.y1, depth_at, tolerance);
  const std::shared_ptr<const PoseState> before = captureState();
  const int group = newGroupNumber(groups_);
  int added = 0;
  for (int v : inside) {
    if (std::find(handles_.begin(), handles_.end(), v) != handles_.end()) continue;
    handles_.push_back(v);
    groups_.push_back(group);
    mirrors_.push_back(-1);
    targets_.insert(targets_.end(), &last_written_[3 * v], &last_written_[3 * v] + 3);
    ++added;
  }
  if (added == 0) {
    log(QStringLiteral("the rectangle holds no visible vertex that is not a handle yet"));
    return;
  }
  active_group_ = group;
  showHandleCount();
  history_.push(new PoseStep(this, QStringLiteral("add group %1 (%2 handles)").arg(group).arg(added), before,
                             captureState()));
  log(QStringLiteral("%1 handles, group %2 of %3 from a rectangle").arg(handles_.size()).arg(group).arg(added));
}

}  // namespace meshik::edit
