// The tool's life: start (a new session or the kept one), the example set and the solve worker,
// applying finished poses, the end of the interactive part.
#include "drag_tool.h"

#include "../layer_arrays.h"

#include <common/mlexception.h>
#include <meshlab/glarea.h>
#include <vcg/complex/algorithms/update/selection.h>

#include <QDockWidget>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace meshik::edit {
namespace {

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

DragTool::DragTool() {
  history_.setUndoLimit(100);  // each step holds a pose: about 1 MB on the elephant
}

DragTool::~DragTool() {
  suspend();
  history_.clear();  // its steps point at this tool
}

QString DragTool::info() {
  return QStringLiteral(
      "MeshIK: Drag to Pose. The current layer is the rest mesh, the other layers with its vertices and "
      "triangles are the example poses. Click vertices to make them handles (shift+click removes one, "
      "ctrl+click adds to the last group), drag a handle: the whole mesh follows inside the space of the "
      "examples. R turns a group, Ctrl+Z undoes.");
}

MeshModel* DragTool::restLayer() const {
  return document_ && rest_id_ >= 0 ? document_->getMesh(static_cast<unsigned>(rest_id_)) : nullptr;
}

void DragTool::report(const QString& error) {
  if (panel_) panel_->showError(error);
  if (document_ && !error.isEmpty()) document_->Log.log(GLLogStream::WARNING, "MeshIK drag: " + error);
}

void DragTool::log(const QString& text) {
  if (document_) document_->Log.log(GLLogStream::FILTER, "MeshIK drag: " + text);
}

bool DragTool::canResume(MeshDocument& document) const {
  if (&document != document_.data() || rest_positions_.empty()) return false;
  const MeshModel* rest = restLayer();
  if (rest == nullptr || rest->cm.vert.size() * 3 != rest_positions_.size()) return false;
  // A layer switch or an import keeps the rest layer; another current layer with triangles
  // starts a new session on that layer while there is no handle and no history yet (a layer still
  // being loaded has none).
  const MeshModel* current = document.mm();
  const bool ours = current == rest || std::find(example_ids_.begin(), example_ids_.end(), current->id()) !=
                                           example_ids_.end();
  if (!ours && handles_.empty() && history_.count() == 0 && current->cm.fn > 0) return false;
  const std::vector<double> now = plugin::vertexPositions(*rest);
  return now == rest_positions_ || now == last_written_;
}

void DragTool::forgetSession() {
  document_ = nullptr;
  rest_id_ = -1;
  rest_positions_.clear();
  last_written_.clear();
  handles_.clear();
  groups_.clear();
  targets_.clear();
  mirrors_.clear();
  last_weights_.clear();
  inverted_.clear();
  active_group_ = 0;
  picked_mirror_plane_.reset();
  example_ids_.clear();
  history_.clear();
  keyframes_.clear();
}

bool DragTool::startEdit(MeshDocument& document, GLArea* area, MLSceneGLSharedDataContext* shared) {
  suspend();
  if (document.mm() == nullptr || area == nullptr) return false;
  const bool resumed = canResume(document);
  if (!resumed) forgetSession();
  document_ = &document;
  area_ = area;
  shared_ = shared;
  if (!resumed) rest_id_ = document.mm()->id();
  MeshModel* rest = restLayer();

  dock_ = new QDockWidget(area->window());
  dock_->setWindowTitle(QStringLiteral("MeshIK: Drag to Pose"));
  panel_ = new DragDock(dock_);
  dock_->setWidget(panel_);
  dock_->setAllowedAreas(Qt::NoDockWidgetArea);
  dock_->setFloating(true);
  // Over the right edge of the main window (its layer list), leaving the 3D view free.
  const QRect window = area->window()->geometry();
  dock_->setGeometry(window.right() - 340, window.top() + 60, 330, std::min(window.height() - 80, 760));
  dock_->setVisible(true);
  connect(panel_, &DragDock::examplesChanged, this, &DragTool::rebuildExamples);
  connect(panel_, &DragDock::optionsChanged, this, &DragTool::restartWorker);
  connect(panel_, &DragDock::mirrorChanged, this, &DragTool::mirrorModeChanged);
  connect(panel_, &DragDock::resetPose, this, &DragTool::resetPose);
  connect(panel_, &DragDock::clearHandles, this, &DragTool::clearHandles);
  connect(panel_, &DragDock::addKeyframe, this, &DragTool::addKeyframe);
  connect(panel_, &DragDock::clearKeyframes, this, &DragTool::clearKeyframes);
  connect(panel_, &DragDock::saveConstraintFile, this, &DragTool::saveConstraintFile);
  connect(panel_, &DragDock::savePose, this, &DragTool::savePose);
  connect(panel_, &DragDock::poseToNewLayer, this, &DragTool::poseToNewLayer);
  area->installEventFilter(this);

  try {
    plugin::compactLayer(*rest);
    if (rest->cm.fn == 0) throw MLException("the rest layer " + plugin::describeLayer(*rest) + " has no triangles");
    std::vector<std::pair<QString, int>> candidates;
    for (MeshModel& layer : document.meshIterator())
      if (plugin::isDefaultExample(layer, *rest, nullptr)) candidates.emplace_back(layer.label(), layer.id());
    panel_->setExampleLayers(candidates);
    if (resumed) {
      log(QStringLiteral("resumed on the rest layer %1 with %2 handles, %3 undo steps (the rest pose kept)")
              .arg(plugin::describeLayer(*rest))
              .arg(handles_.size())
              .arg(history_.count()));
      next_start_weights_ = last_weights_;
    } else {
      rest_positions_ = plugin::vertexPositions(*rest);
      last_written_ = rest_positions_;
      handles_ = plugin::selectedVertices(*rest);  // a selection made before is one group
      groups_.assign(handles_.size(), 1);
      mirrors_.assign(handles_.size(), -1);
      active_group_ = handles_.empty() ? 0 : 1;
      for (int v : handles_) targets_.insert(targets_.end(), &rest_positions_[3 * v], &rest_positions_[3 * v] + 3);
    }
    layer_has_selection_ = !plugin::selectedVertices(*rest).empty() ||
                           vcg::tri::UpdateSelection<CMeshO>::FaceCount(rest->cm) > 0;
    showHandleCount();
    panel_->showKeyframes(keyframes_.count());
  } catch (const std::exception& error) {  // MLException and anything else: never into MeshLab
    report(error.what());
    return true;  // the dock shows the error; nothing else happens until the user fixes the layers
  }
  shadeSmoothWhilePosing(*rest);
  rebuildExamples();
  area->setFocus();  // the tool's keys (P, S, R, Ctrl+Z...) work at once, before any click on the view
  area->update();
  return true;
}

void DragTool::rebuildExamples() {
  MeshModel* rest = restLayer();
  if (rest == nullptr || !panel_) return;
  worker_.reset();
  example_set_.reset();
  try {
    QStringList ids;
    for (int id : panel_->checkedExampleLayers()) ids << QString::number(id);
    if (ids.isEmpty()) throw MLException("no example layer: open the example poses as layers beside the rest mesh");
    triangles_ = plugin::triangleIndices(*rest);
    const std::vector<MeshModel*> examples = plugin::exampleLayers(*document_, *rest, triangles_, ids.join(","), nullptr);
    std::vector<std::vector<double>> positions;
    std::vector<const double*> pointers;
    std::vector<QString> names;
    example_ids_.clear();
    for (MeshModel* example : examples) {
      positions.push_back(plugin::vertexPositions(*example));
      example_ids_.push_back(example->id());
      names.push_back(example->label());
    }
    for (const auto& p : positions) pointers.push_back(p.data());
    const MeshView view{rest_positions_.data(), static_cast<int>(rest_positions_.size() / 3), triangles_.data(),
                        static_cast<int>(triangles_.size() / 3)};
    try {
      example_set_ = std::make_shared<const ExampleSet>(view, pointers);
    } catch (const InputError& error) {
      throw MLException(QString::fromUtf8(error.what()) + " (rest layer " + plugin::describeLayer(*rest) + ")");
    }
    panel_->setWeightNames(names);
    report(QString());
    log(QStringLiteral("rest layer %1, %2 example layers, %3 handles")
            .arg(plugin::describeLayer(*rest))
            .arg(examples.size())
            .arg(handles_.size()));
  } catch (const std::exception& error) {
    report(error.what());
    return;
  }
  restartWorker();
}

void DragTool::restartWorker() {
  if (!example_set_ || !panel_) return;
  worker_.reset();
  SolverOptions options;
  options.feature_space = panel_->linearFeatureSpace() ? FeatureSpace::kLinear : FeatureSpace::kNonlinear;
  options.weight_regularization = panel_->weightRegularization();
  options.blend = panel_->freeBlend() ? Blend::kFree : Blend::kAffine;
  options.regions = panel_->regionCount();
  options.region_smoothness = panel_->regionSmoothness();
  options.handle_stiffness = panel_->handleStiffness();
  worker_ = std::make_unique<SolveWorker>(
      example_set_, options, [this] { QMetaObject::invokeMethod(this, "applyFinishedPose", Qt::QueuedConnection); },
      triangles_);
  if (!handles_.empty() && last_written_ != rest_positions_) {
    next_start_weights_ = last_weights_;
    postSolve(false, Clock::now());  // the pose so far, solved again (to convergence) with the options
  }
}

void DragTool::suspend() {
  worker_.reset();  // joins the worker: no solve runs and no notification comes after this
  if (step_before_ && (drag_ || rotation_)) restoreState(*step_before_, QStringLiteral("cancel (the tool ended)"));
  drag_.reset();
  rotation_.reset();
  step_before_.reset();
  typed_degrees_.clear();
  rotation_dragging_ = false;
  if (navigating_ && area_) area_->suspendedEditor = false;
  navigating_ = false;
  pending_click_.reset();
  pending_rectangle_.reset();
  pressed_.reset();
  rectangle_.reset();
  projection_.reset();
  example_set_.reset();
  timings_.clear();
  converged_solve_ = false;
  restoreArtistShading();
  if (area_) area_->removeEventFilter(this);
  delete dock_.data();  // deletes the panel too (null when MeshLab's window already deleted it)
  dock_ = nullptr;
  panel_ = nullptr;
  area_ = nullptr;
  shared_ = nullptr;
}

void DragTool::endEdit(MeshDocument&, GLArea*, MLSceneGLSharedDataContext*) { suspend(); }

void DragTool::endEdit(MeshModel&, GLArea*, MLSceneGLSharedDataContext*) { suspend(); }

void DragTool::layerChanged(MeshDocument& document, MeshModel&, GLArea* area, MLSceneGLSharedDataContext*) {
  if (&document == document_.data() && restLayer() != nullptr) {
    if (area) area->update();
    return;
  }
  startEdit(document, area, shared_);  // the rest layer is gone (deleted): start on the current one
}

void DragTool::postSolve(bool quick, Clock::time_point event_time) {
  if (!worker_ || handles_.empty()) return;
  SolveRequest request;
  request.quick = quick;
  request.handles = handles_;
  request.targets = targets_;
  request.start_weights = std::move(next_start_weights_);
  next_start_weights_.reset();
  request.first_event = event_time;
  worker_->post(std::move(request));
}

void DragTool::applyFinishedPose() {
  if (!worker_) return;
  if (std::optional<SolveOutcome> outcome = worker_->take()) {
    applyOutcome(*outcome);
    worker_->poseWritten();  // the next solve may start: it no longer competes with the write
  }
}

void DragTool::finishPendingSolve() {
  if (!worker_) return;
  worker_->waitIdle();
  applyFinishedPose();
}

void DragTool::convergeNow() {
  finishPendingSolve();
  converged_solve_ = true;  // the pose left in the layer is a converged one
  postSolve(false, Clock::now());
  finishPendingSolve();
  converged_solve_ = false;
}

void DragTool::applyOutcome(const SolveOutcome& outcome) {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  if (!outcome.error.empty()) {
    report(QString::fromStdString(outcome.error));
    return;
  }
  if (outcome.result.vertices.size() != 3 * rest->cm.vert.size()) return;  // the layer changed under us
  const PoseWriteTimes write = writePose(*rest, outcome.result.vertices, outcome.normals);
  last_weights_ = outcome.result.weights;
  inverted_ = outcome.result.inverted_triangles;
  const double latency_ms = millisecondsSince(outcome.request.first_event);
  const double waiting_ms = std::chrono::duration<double, std::milli>(write.start - outcome.finished).count();
  if (drag_ || rotation_) {
    timings_.latency.add(latency_ms);
    timings_.solve.add(outcome.solve_ms);
    timings_.overhead.add(waiting_ms + write.writing_ms + write.backlog_ms);
    timings_.waiting.add(waiting_ms);
    timings_.writing.add(write.writing_ms);
    timings_.buffers.add(write.buffers_ms);
    timings_.backlog.add(write.backlog_ms);
  }
  if (panel_) {
    panel_->showError(QString());
    panel_->showPose(outcome.result.weights, outcome.result.iterations, outcome.solve_ms,
                     static_cast<int>(outcome.result.inverted_triangles.size()));
  }
  log(QStringLiteral("%1 %2 (%3 moves%4), %5 iterations, factor %6 ms, solve %7 ms, latency %8 ms (%9 ms waiting "
                     "for the GUI thread, %10 ms writing the layer and its GL buffers: copy %11 ms, MeshLab's GL "
                     "buffers %12 ms (%13), selection overlay %14 ms; renderer backlog %15 ms), %16 inverted "
                     "triangles")
          .arg(converged_solve_ ? "converged solve" : "solve")
          .arg(outcome.number)
          .arg(outcome.request.moves)
          .arg(outcome.refactored ? ", new handle set" : "")
          .arg(outcome.result.iterations)
          .arg(outcome.factor_ms, 0, 'f', 1)
          .arg(outcome.solve_ms, 0, 'f', 1)
          .arg(latency_ms, 0, 'f', 1)
          .arg(waiting_ms, 0, 'f', 1)
          .arg(write.writing_ms, 0, 'f', 1)
          .arg(write.copy_ms, 0, 'f', 2)
          .arg(write.buffers_ms, 0, 'f', 2)
          .arg(write.replicated ? "flat shading: 3 vertices per triangle" : "indexed")
          .arg(write.selection_ms, 0, 'f', 2)
          .arg(write.backlog_ms, 0, 'f', 2)
          .arg(outcome.result.inverted_triangles.size()));
}

PoseWriteTimes DragTool::writePose(MeshModel& rest, const std::vector<double>& positions,
                                   const SurfaceNormals& normals) {
  if (normals.vertices.size() != positions.size() || normals.faces.size() != 3 * rest.cm.face.size()) {
    // Not from the worker (undo, redo, reset): computed here, off the path of a drag.
    return writePose(rest, positions, surfaceNormals(positions, plugin::triangleIndices(rest)));
  }
  const Clock::time_point start = Clock::now();
  plugin::setVertexPositionsAndNormals(rest, positions, normals.faces, normals.vertices, last_written_);
  const double copy_ms = millisecondsSince(start);
  PoseWriteTimes times = refreshBuffers(rest);
  times.start = start;
  times.copy_ms = copy_ms;
  times.writing_ms = millisecondsSince(start) - times.backlog_ms;
  return times;
}

PoseWriteTimes DragTool::refreshBuffers(MeshModel& layer) {
  PoseWriteTimes times;
  if (area_ != nullptr) {  // what the view's renderer still had to draw (its own GL context)
    const Clock::time_point finishing = Clock::now();
    area_->makeCurrent();
    glFinish();
    times.backlog_ms = millisecondsSince(finishing);
  }
  if (shared_ != nullptr) {
    const Clock::time_point uploading = Clock::now();
    MLRenderingData::RendAtts attributes;
    attributes[MLRenderingData::ATT_NAMES::ATT_VERTPOSITION] = true;
    attributes[MLRenderingData::ATT_NAMES::ATT_VERTNORMAL] = true;
    attributes[MLRenderingData::ATT_NAMES::ATT_FACENORMAL] = true;
    shared_->meshAttributesUpdated(layer.id(), false, attributes);
    shared_->manageBuffers(layer.id());
    times.buffers_ms = millisecondsSince(uploading);
    times.replicated = drawnFlat(layer);  // face normals: MeshLab uploads 3 vertices per triangle
  }
  if (area_ != nullptr) {
    const Clock::time_point selecting = Clock::now();
    if (layer_has_selection_) area_->updateSelection(layer.id(), true, true);  // the overlay's own copy
    times.selection_ms = millisecondsSince(selecting);
    area_->update();
  }
  return times;
}

void DragTool::poseToNewLayer() {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  finishPendingSolve();
  MeshModel* copy = document_->addNewMesh(rest->cm, plugin::kOutputLabelPrefix + "pose of " + rest->label(), false);
  log(QStringLiteral("pose copied to %1").arg(plugin::describeLayer(*copy)));
}

}  // namespace meshik::edit
