// The tool's file commands: "Save constraint file..." (the keyframes, or the handles of the
// moment as one frame) and "Save pose...".
#include "drag_tool.h"

#include "../layer_arrays.h"
#include "constraint_frames_writer.h"

#include <common/mlexception.h>
#include <common/utilities/load_save.h>
#include <meshlab/glarea.h>

#include <QFileDialog>
#include <QFileInfo>
#include <QStringList>

namespace meshik::edit {
namespace {

// The absolute path of the file a layer was loaded from or saved to; empty when it has none.
std::string layerFile(const MeshModel* layer) {
  if (layer == nullptr || layer->fullName().isEmpty()) return {};
  return QFileInfo(layer->fullName()).absoluteFilePath().toStdString();
}

}  // namespace

QString DragTool::askSavePath(const QString& title, const QString& file_name, const QString& filter) {
  MeshModel* rest = restLayer();
  if (rest == nullptr || area_ == nullptr) return {};
  finishPendingSolve();  // what is saved is the newest pose
  const QString start = QFileInfo(rest->fullName()).absolutePath() + "/" + file_name;
  return QFileDialog::getSaveFileName(area_->window(), title, start, filter, nullptr,
                                      QFileDialog::DontUseNativeDialog);
}

void DragTool::saveConstraintFile() {
  const QString path = askSavePath(tr("Save constraint file"), "drag.json", tr("MeshIK constraint files (*.json)"));
  if (path.isEmpty()) return;
  DragFrames file;
  file.rest_path = layerFile(restLayer());
  for (int id : example_ids_) file.example_paths.push_back(layerFile(document_->getMesh(static_cast<unsigned>(id))));
  file.linear_feature_space = panel_ && panel_->linearFeatureSpace();
  file.weight_regularization = panel_ ? panel_->weightRegularization() : 0.0;
  file.free_blend = panel_ && panel_->freeBlend();
  file.regions = panel_ ? panel_->regionCount() : 1;
  file.region_smoothness = panel_ ? panel_->regionSmoothness() : 0.01;
  file.handle_stiffness = panel_ ? panel_->handleStiffness() : 0.0;
  if (keyframes_.count() > 0) keyframes_.fill(file);
  else fillOneFrame(file, "drag", handles_, groups_, targets_);
  try {
    writeConstraintFrames(path.toStdString(), file, rest_positions_.data(), static_cast<int>(rest_positions_.size() / 3));
    log(QStringLiteral("saved %1 handles in %2 groups, %3 frames to %4")
            .arg(handles_.size())
            .arg(file.groups.size())
            .arg(file.frames.size())
            .arg(path));
  } catch (const std::exception& error) {  // ConstraintWriteError, or no memory for the text
    report(QString::fromStdString(error.what()));
  }
}

void DragTool::savePose() {
  const QString path = askSavePath(tr("Save pose"), "pose.ply", tr("Meshes (*.ply *.obj *.off *.stl)"));
  MeshModel* rest = restLayer();
  if (path.isEmpty() || rest == nullptr) return;
  try {
    const QString rest_file = rest->fullName();
    meshlab::saveMeshWithStandardParameters(path, *rest, &document_->Log);
    // MeshLab renames the layer after the saved file: the layer stays the rest mesh's (its file is
    // what the constraint files name as the rest).
    if (!rest_file.isEmpty()) rest->setFileName(rest_file);
    QStringList weights;  // in full: they are the warm start that reproduces this pose
    for (double w : last_weights_) weights << QString::number(w, 'g', 17);
    log(QStringLiteral("saved the pose to %1 (weights [%2])").arg(path, weights.join(", ")));
  } catch (const std::exception& error) {  // MLException from MeshLab's IO plugins, and the rest
    report(error.what());
  }
}

}  // namespace meshik::edit
