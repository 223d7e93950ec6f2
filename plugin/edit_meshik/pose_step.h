// One step of the tool's undo history (a QUndoCommand, as edit_paint keeps its strokes): the
// states before and after a drag, a turn, a handle added or removed, a reset or a clear.
// Consecutive steps share their states (the after of one is the before of the next).
#pragma once

#include "pose_state.h"

#include <QUndoCommand>

#include <memory>

namespace meshik::edit {

class DragTool;

class PoseStep : public QUndoCommand {
 public:
  // tool: whose restoreState undo and redo call; text: what the step did ("drag group 2", ...).
  PoseStep(DragTool* tool, const QString& text, std::shared_ptr<const PoseState> before,
           std::shared_ptr<const PoseState> after);
  void undo() override;
  // Puts the after state back, except the first time (QUndoStack::push calls it on a step the
  // tool has just done).
  void redo() override;

 private:
  DragTool* tool_;
  std::shared_ptr<const PoseState> before_, after_;
  bool done_ = true;
};

}  // namespace meshik::edit
