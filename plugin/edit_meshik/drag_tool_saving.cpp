// The tool's file commands: "Save constraint file..." and "Save pose...".
#include "drag_tool.h"

#include "constraint_frame_writer.h"

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
  DragFrame frame;
  frame.rest_path = layerFile(restLayer());
  for (int id : example_ids_) frame.example_paths.push_back(layerFile(document_->getMesh(static_cast<unsigned>(id))));
  frame.linear_feature_space = panel_ && panel_->linearFeatureSpace();
  frame.weight_regularization = panel_ ? panel_->weightRegularization() : 0.0;
  frame.handles = handles_;
  frame.targets = targets_;
  try {
    writeConstraintFrame(path.toStdString(), frame);
    document_->Log.log(GLLogStream::FILTER,
                       QStringLiteral("MeshIK drag: saved %1 handles to %2").arg(handles_.size()).arg(path));
  } catch (const std::exception& error) {  // ConstraintWriteError, or no memory for the text
    report(QString::fromStdString(error.what()));
  }
}

void DragTool::savePose() {
  const QString path = askSavePath(tr("Save pose"), "pose.ply", tr("Meshes (*.ply *.obj *.off *.stl)"));
  MeshModel* rest = restLayer();
  if (path.isEmpty() || rest == nullptr) return;
  try {
    meshlab::saveMeshWithStandardParameters(path, *rest, &document_->Log);
    QStringList weights;  // in full: they are the warm start that reproduces this pose
    for (double w : last_weights_) weights << QString::number(w, 'g', 17);
    document_->Log.log(GLLogStream::FILTER,
                       QStringLiteral("MeshIK drag: saved the pose to %1 (weights [%2])").arg(path, weights.join(", ")));
  } catch (const std::exception& error) {  // MLException from MeshLab's IO plugins, and the rest
    report(error.what());
  }
}

}  // namespace meshik::edit
