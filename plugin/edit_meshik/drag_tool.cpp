#include "drag_tool.h"

#include "../layer_arrays.h"
#include "vertex_picking.h"

#include <common/mlexception.h>
#include <meshlab/glarea.h>
#include <vcg/complex/algorithms/update/selection.h>

#include <QDockWidget>
#include <QKeyEvent>
#include <QMouseEvent>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace meshik::edit {
namespace {

constexpr double kHandleRadiusPixels = 10.0;  // a press this close to a handle's marker grabs it
constexpr double kPickRadiusPixels = 12.0;    // a click this close to a vertex picks it

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

DragTool::DragTool() = default;

DragTool::~DragTool() { finish(); }

QString DragTool::info() {
  return QStringLiteral(
      "MeshIK: Drag to Pose. The current layer is the rest mesh, the other layers with its vertices and "
      "triangles are the example poses. Click vertices to make them handles (shift+click removes one), "
      "drag a handle: the whole mesh follows inside the space of the examples.");
}

MeshModel* DragTool::restLayer() const {
  return document_ && rest_id_ >= 0 ? document_->getMesh(static_cast<unsigned>(rest_id_)) : nullptr;
}

void DragTool::report(const QString& error) {
  if (panel_) panel_->showError(error);
  if (document_ && !error.isEmpty()) document_->Log.log(GLLogStream::WARNING, "MeshIK drag: " + error);
}

bool DragTool::startEdit(MeshDocument& document, GLArea* area, MLSceneGLSharedDataContext* shared) {
  finish();
  document_ = &document;
  area_ = area;
  shared_ = shared;
  MeshModel* rest = document.mm();
  if (rest == nullptr || area == nullptr) return false;
  rest_id_ = rest->id();

  dock_ = new QDockWidget(area->window());
  dock_->setWindowTitle(QStringLiteral("MeshIK: Drag to Pose"));
  panel_ = new DragDock(dock_);
  dock_->setWidget(panel_);
  dock_->setAllowedAreas(Qt::NoDockWidgetArea);
  dock_->setFloating(true);
  // Over the right edge of the main window (its layer list), leaving the 3D view free.
  const QRect window = area->window()->geometry();
  dock_->setGeometry(window.right() - 330, window.top() + 60, 320, std::min(window.height() - 80, 660));
  dock_->setVisible(true);
  connect(panel_, &DragDock::examplesChanged, this, &DragTool::rebuildExamples);
  connect(panel_, &DragDock::optionsChanged, this, &DragTool::restartWorker);
  connect(panel_, &DragDock::resetPose, this, &DragTool::resetPose);
  connect(panel_, &DragDock::clearHandles, this, &DragTool::clearHandles);
  connect(panel_, &DragDock::saveConstraintFile, this, &DragTool::saveConstraintFile);
  connect(panel_, &DragDock::savePose, this, &DragTool::savePose);
  connect(panel_, &DragDock::poseToNewLayer, this, &DragTool::poseToNewLayer);

  try {
    plugin::compactLayer(*rest);
    if (rest->cm.fn == 0) throw MLException("the rest layer " + plugin::describeLayer(*rest) + " has no triangles");
    rest_positions_ = plugin::vertexPositions(*rest);
    std::vector<std::pair<QString, int>> candidates;
    for (MeshModel& layer : document.meshIterator())
      if (plugin::isDefaultExample(layer, *rest, nullptr)) candidates.emplace_back(layer.label(), layer.id());
    panel_->setExampleLayers(candidates);
    handles_ = plugin::selectedVertices(*rest);
    layer_has_selection_ = !handles_.empty() || vcg::tri::UpdateSelection<CMeshO>::FaceCount(rest->cm) > 0;
    for (int v : handles_) targets_.insert(targets_.end(), &rest_positions_[3 * v], &rest_positions_[3 * v] + 3);
    panel_->showHandles(static_cast<int>(handles_.size()));
  } catch (const std::exception& error) {  // MLException and anything else: never into MeshLab
    report(error.what());
    return true;  // the dock shows the error; nothing else happens until the user fixes the layers
  }
  rebuildExamples();
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
    const std::vector<int> triangles = plugin::triangleIndices(*rest);
    const std::vector<MeshModel*> examples = plugin::exampleLayers(*document_, *rest, triangles, ids.join(","), nullptr);
    std::vector<std::vector<double>> positions;
    std::vector<const double*> pointers;
    example_ids_.clear();
    for (MeshModel* example : examples) {
      positions.push_back(plugin::vertexPositions(*example));
      example_ids_.push_back(example->id());
    }
    for (const auto& p : positions) pointers.push_back(p.data());
    const MeshView view{rest_positions_.data(), static_cast<int>(rest_positions_.size() / 3), triangles.data(),
                        static_cast<int>(triangles.size() / 3)};
    try {
      example_set_ = std::make_shared<const ExampleSet>(view, pointers);
    } catch (const InputError& error) {
      throw MLException(QString::fromUtf8(error.what()) + " (rest layer " + plugin::describeLayer(*rest) + ")");
    }
    report(QString());
    document_->Log.log(GLLogStream::FILTER, QStringLiteral("MeshIK drag: rest layer %1, %2 example layers, %3 handles")
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
  worker_ = std::make_unique<SolveWorker>(example_set_, options, [this] {
    QMetaObject::invokeMethod(this, "applyFinishedPose", Qt::QueuedConnection);
  });
  if (!handles_.empty() && restLayer() != nullptr && plugin::vertexPositions(*restLayer()) != rest_positions_)
    postSolve(false, Clock::now());  // the pose so far, solved again (to convergence) with the new options
}

void DragTool::finish() {
  worker_.reset();  // joins the worker: no solve runs and no notification comes after this
  drag_.reset();
  pending_click_.reset();
  projection_.reset();
  example_set_.reset();
  handles_.clear();
  targets_.clear();
  rest_positions_.clear();
  example_ids_.clear();
  last_weights_.clear();
  latency_.clear();
  cold_start_next_ = false;
  converged_solve_ = false;
  layer_has_selection_ = false;
  delete dock_.data();  // deletes the panel too (null when MeshLab's window already deleted it)
  dock_ = nullptr;
  panel_ = nullptr;
  rest_id_ = -1;
  document_ = nullptr;
  area_ = nullptr;
  shared_ = nullptr;
}

void DragTool::endEdit(MeshDocument&, GLArea*, MLSceneGLSharedDataContext*) { finish(); }

void DragTool::endEdit(MeshModel&, GLArea*, MLSceneGLSharedDataContext*) { finish(); }

void DragTool::postSolve(bool quick, Clock::time_point event_time) {
  if (!worker_ || handles_.empty()) return;
  SolveRequest request;
  request.quick = quick;
  request.handles = handles_;
  request.targets = targets_;
  request.cold_start = cold_start_next_;
  cold_start_next_ = false;
  request.first_event = event_time;
  worker_->post(std::move(request));
}

void DragTool::applyFinishedPose() {
  if (!worker_) return;
  if (std::optional<SolveOutcome> outcome = worker_->take()) applyOutcome(*outcome);
}

void DragTool::finishPendingSolve() {
  if (!worker_) return;
  worker_->waitIdle();
  applyFinishedPose();
}

void DragTool::applyOutcome(const SolveOutcome& outcome) {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  if (!outcome.error.empty()) {
    report(QString::fromStdString(outcome.error));
    return;
  }
  if (outcome.result.vertices.size() != 3 * rest->cm.vert.size()) return;  // the layer changed under us
  const Clock::time_point applying = Clock::now();
  plugin::setVertexPositions(*rest, outcome.result.vertices);  // positions, normals, bounding box
  last_weights_ = outcome.result.weights;
  refreshBuffers(*rest);
  const double latency_ms = millisecondsSince(outcome.request.first_event);
  const double waiting_ms = std::chrono::duration<double, std::milli>(applying - outcome.finished).count();
  const double buffers_ms = millisecondsSince(applying);
  if (drag_) latency_.add(latency_ms);
  if (panel_) {
    panel_->showError(QString());
    panel_->showPose(outcome.result.weights, outcome.result.iterations, outcome.solve_ms,
                     static_cast<int>(outcome.result.inverted_triangles.size()));
  }
  document_->Log.log(GLLogStream::FILTER,
                     QStringLiteral("MeshIK drag: %11 %1 (%2 moves%3), %4 iterations, factor %5 ms, solve %6 ms, "
                                    "latency %7 ms (%9 ms waiting for the GUI thread, %10 ms writing the layer and "
                                    "its GL buffers), %8 inverted triangles")
                         .arg(outcome.number)
                         .arg(outcome.request.moves)
                         .arg(outcome.refactored ? ", new handle set" : "")
                         .arg(outcome.result.iterations)
                         .arg(outcome.factor_ms, 0, 'f', 1)
                         .arg(outcome.solve_ms, 0, 'f', 1)
                         .arg(latency_ms, 0, 'f', 1)
                         .arg(outcome.result.inverted_triangles.size())
                         .arg(waiting_ms, 0, 'f', 1)
                         .arg(buffers_ms, 0, 'f', 1)
                         .arg(converged_solve_ ? "converged solve" : "solve"));
}

void DragTool::refreshBuffers(MeshModel& layer) {
  if (shared_ != nullptr) {
    MLRenderingData::RendAtts attributes;
    attributes[MLRenderingData::ATT_NAMES::ATT_VERTPOSITION] = true;
    attributes[MLRenderingData::ATT_NAMES::ATT_VERTNORMAL] = true;
    attributes[MLRenderingData::ATT_NAMES::ATT_FACENORMAL] = true;
    shared_->meshAttributesUpdated(layer.id(), false, attributes);
    shared_->manageBuffers(layer.id());
  }
  if (area_ != nullptr) {
    if (layer_has_selection_) area_->updateSelection(layer.id(), true, true);  // the overlay's own copy
    area_->update();
  }
}

std::pair<double, double> DragTool::glPosition(const QMouseEvent* event) const {
  const double scale = area_ ? area_->devicePixelRatioF() : 1.0;
  const double height = area_ ? area_->height() : 0.0;
  return {event->x() * scale, (height - event->y()) * scale};
}

void DragTool::mousePressEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) {
  if (event->button() != Qt::LeftButton || layer.id() != rest_id_) return;
  const auto [x, y] = glPosition(event);
  const bool remove = event->modifiers() & Qt::ShiftModifier;
  if (!remove && projection_ && worker_) {
    const int grabbed = pickHandle(*projection_, targets_, x, y, kHandleRadiusPixels);
    if (grabbed >= 0) {
      std::vector<int> group;  // the selected handles move with the grabbed one
      if (layer.cm.vert[handles_[grabbed]].IsS())
        for (size_t h = 0; h < handles_.size(); ++h)
          if (layer.cm.vert[handles_[h]].IsS()) group.push_back(static_cast<int>(h));
      drag_.emplace(*projection_, targets_, grabbed, group, x, y);
      latency_.clear();
      drag_start_counts_ = worker_->counts();
      area->update();
      return;
    }
  }
  pending_click_ = Click{x, y, remove};
  area->update();
}

void DragTool::mouseMoveEvent(QMouseEvent* event, MeshModel&, GLArea* area) {
  if (!drag_) return;
  const Clock::time_point now = Clock::now();
  const auto [x, y] = glPosition(event);
  targets_ = drag_->targetsAt(x, y);
  postSolve(true, now);  // one warm-started Gauss-Newton step per move; the release converges
  area->update();
}

void DragTool::mouseReleaseEvent(QMouseEvent*, MeshModel&, GLArea* area) {
  if (!drag_ || !worker_) return;
  finishPendingSolve();
  const SolveWorker::Counts counts = worker_->counts();
  drag_.reset();
  converged_solve_ = true;  // the pose left in the layer is a converged one
  postSolve(false, Clock::now());
  finishPendingSolve();
  converged_solve_ = false;
  const QString summary =
      QStringLiteral("MeshIK drag: %1 moves, %2 solves (%3 coalesced, %4 superseded), latency median %5 ms, max %6 ms")
          .arg(counts.moves - drag_start_counts_.moves)
          .arg(counts.solves - drag_start_counts_.solves)
          .arg(counts.coalesced - drag_start_counts_.coalesced)
          .arg(counts.superseded - drag_start_counts_.superseded)
          .arg(latency_.median(), 0, 'f', 1)
          .arg(latency_.max(), 0, 'f', 1);
  document_->Log.log(GLLogStream::FILTER, summary);
  if (panel_) panel_->showLatency(summary.mid(QStringLiteral("MeshIK drag: ").size()));
  area->update();
}

void DragTool::keyPressEvent(QKeyEvent* event, MeshModel&, GLArea*) {
  switch (event->key()) {
    case Qt::Key_S: saveConstraintFile(); break;
    case Qt::Key_P: savePose(); break;
    case Qt::Key_R: resetPose(); break;
    case Qt::Key_C: clearHandles(); break;
    case Qt::Key_N: poseToNewLayer(); break;
    default: return;
  }
  event->accept();
}

void DragTool::handleClick(const Click& click, MeshModel& layer) {
  int handle = pickHandle(*projection_, targets_, click.x, click.y, kHandleRadiusPixels);
  if (handle < 0 || !click.remove) {
    float depth = 1.0f;
    glReadPixels(static_cast<GLint>(click.x), static_cast<GLint>(click.y), 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
    const int vertex = pickVertex(*projection_, plugin::vertexPositions(layer), click.x, click.y, depth, kPickRadiusPixels);
    if (vertex < 0) return;
    const auto found = std::find(handles_.begin(), handles_.end(), vertex);
    if (click.remove) {
      if (found == handles_.end()) return;
      handle = static_cast<int>(found - handles_.begin());
    } else {
      if (found != handles_.end()) return;
      handles_.push_back(vertex);
      for (int k = 0; k < 3; ++k) targets_.push_back(static_cast<double>(layer.cm.vert[vertex].cP()[k]));
    }
  }
  if (click.remove) {
    handles_.erase(handles_.begin() + handle);
    targets_.erase(targets_.begin() + 3 * handle, targets_.begin() + 3 * handle + 3);
  }
  QString where;
  if (!click.remove) {  // where the new handle's marker is on the screen (for scripts driving the GUI)
    const WindowPoint w = projection_->project(&targets_[targets_.size() - 3]);
    const double scale = area_->devicePixelRatioF();
    const QPoint screen = area_->mapToGlobal(QPoint(static_cast<int>(std::lround(w.x / scale)),
                                                    static_cast<int>(std::lround(area_->height() - w.y / scale))));
    where = QStringLiteral(", the new one vertex %1 at screen %2 %3").arg(handles_.back()).arg(screen.x()).arg(screen.y());
  }
  document_->Log.log(GLLogStream::FILTER, QStringLiteral("MeshIK drag: %1 handles%2").arg(handles_.size()).arg(where));
  if (panel_) panel_->showHandles(static_cast<int>(handles_.size()));
  // No solve here: a new handle holds its vertex where it is, so the pose does not jump; the next
  // move solves with the new handle set (and refactors then).
  if (area_) area_->update();
}

void DragTool::decorate(MeshModel& layer, GLArea* area, QPainter*) {
  if (layer.id() != rest_id_) return;
  glPushMatrix();
  glMultMatrix(layer.cm.Tr);
  double projection[16], modelview[16];
  GLint viewport[4];
  glGetDoublev(GL_PROJECTION_MATRIX, projection);
  glGetDoublev(GL_MODELVIEW_MATRIX, modelview);
  glGetIntegerv(GL_VIEWPORT, viewport);
  projection_.emplace(projection, modelview, viewport);
  if (pending_click_) {
    const Click click = *pending_click_;
    pending_click_.reset();
    handleClick(click, layer);
  }
  // The handles' targets as points over the mesh: the grabbed one red, the others yellow.
  glPushAttrib(GL_ENABLE_BIT | GL_POINT_BIT | GL_CURRENT_BIT);
  glDisable(GL_LIGHTING);
  glDisable(GL_DEPTH_TEST);
  glPointSize(9.0f * static_cast<float>(area->devicePixelRatioF()));
  glBegin(GL_POINTS);
  for (size_t h = 0; h < handles_.size(); ++h) {
    if (drag_ && static_cast<int>(h) == drag_->grabbed()) glColor3f(1.0f, 0.1f, 0.1f);
    else glColor3f(1.0f, 0.85f, 0.0f);
    glVertex3d(targets_[3 * h], targets_[3 * h + 1], targets_[3 * h + 2]);
  }
  glEnd();
  glPopAttrib();
  glPopMatrix();
}

void DragTool::resetPose() {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  if (worker_) worker_->waitIdle();
  if (worker_) worker_->take();
  for (size_t h = 0; h < handles_.size(); ++h)
    for (int k = 0; k < 3; ++k) targets_[3 * h + k] = rest_positions_[3 * handles_[h] + k];
  plugin::setVertexPositions(*rest, rest_positions_);
  refreshBuffers(*rest);
  last_weights_.assign(last_weights_.size(), 0.0);
  if (panel_) panel_->showPose(last_weights_, 0, 0.0, 0);
  cold_start_next_ = true;  // the next solve starts afresh, not from the last pose's weights
}

void DragTool::clearHandles() {
  handles_.clear();
  targets_.clear();
  drag_.reset();
  if (panel_) panel_->showHandles(0);
  if (area_) area_->update();
}

void DragTool::poseToNewLayer() {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  finishPendingSolve();
  MeshModel* copy = document_->addNewMesh(rest->cm, plugin::kOutputLabelPrefix + "pose of " + rest->label(), false);
  document_->Log.log(GLLogStream::FILTER, QStringLiteral("MeshIK drag: pose copied to %1").arg(plugin::describeLayer(*copy)));
}

}  // namespace meshik::edit
