#include "pose_step.h"

#include "drag_tool.h"

#include <utility>

namespace meshik::edit {

PoseStep::PoseStep(DragTool* tool, const QString& text, std::shared_ptr<const PoseState> before,
                   std::shared_ptr<const PoseState> after)
    : QUndoCommand(text), tool_(tool), before_(std::move(before)), after_(std::move(after)) {}

void PoseStep::undo() { tool_->restoreState(*before_, QStringLiteral("undo ") + text()); }

void PoseStep::redo() {
  if (done_) {
    done_ = false;
    return;
  }
  tool_->restoreState(*after_, QStringLiteral("redo ") + text());
}

}  // namespace meshik::edit
