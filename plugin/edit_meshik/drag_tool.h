// "MeshIK: Drag to Pose": the MeshLab edit tool. The current layer is the rest mesh, the other
// layers with its vertices and triangles are the examples; click vertices to make them handles,
// drag a handle and the pose follows (solved on a worker thread, coalescing mouse moves, written
// into the layer on the GUI thread only). The thin Qt/GL adapter over the GL-free logic in logic/.
#pragma once

#include "drag_dock.h"
#include "latency_stats.h"
#include "screen_projection.h"
#include "solve_worker.h"
#include "view_plane_drag.h"

#include <common/plugins/interfaces/edit_plugin.h>

#include <QDockWidget>
#include <QObject>
#include <QPointer>

#include <memory>
#include <optional>
#include <vector>

namespace meshik::edit {

class DragTool : public QObject, public EditTool {
  Q_OBJECT

 public:
  DragTool();
  ~DragTool() override;
  static QString info();

  bool startEdit(MeshDocument& document, GLArea* area, MLSceneGLSharedDataContext* shared) override;
  void endEdit(MeshDocument& document, GLArea* area, MLSceneGLSharedDataContext* shared) override;
  void endEdit(MeshModel& layer, GLArea* area, MLSceneGLSharedDataContext* shared) override;
  void decorate(MeshModel& layer, GLArea* area, QPainter* painter) override;
  void mousePressEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) override;
  void mouseMoveEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) override;
  void mouseReleaseEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) override;
  void keyPressEvent(QKeyEvent* event, MeshModel& layer, GLArea* area) override;

 private slots:
  void applyFinishedPose();  // on the GUI thread, after the worker finished a request
  void rebuildExamples();
  void restartWorker();
  void resetPose();
  void clearHandles();
  void saveConstraintFile();
  void savePose();
  void poseToNewLayer();

 private:
  struct Click {
    double x, y;  // GL window pixels
    bool remove;  // shift+click
  };

  void finish();
  // Asks for a file to save to (title, suggested name beside the rest mesh's file, filter) once
  // the newest pose is in the layer; empty when cancelled or when the tool is not running.
  QString askSavePath(const QString& title, const QString& file_name, const QString& filter);
  MeshModel* restLayer() const;
  void report(const QString& error);
  // Posts the handles' current targets; quick: one Gauss-Newton step (a move during a drag).
  void postSolve(bool quick, Clock::time_point event_time);
  void applyOutcome(const SolveOutcome& outcome);
  void handleClick(const Click& click, MeshModel& layer);
  void finishPendingSolve();
  void refreshBuffers(MeshModel& layer);
  std::pair<double, double> glPosition(const QMouseEvent* event) const;

  MeshDocument* document_ = nullptr;
  GLArea* area_ = nullptr;
  MLSceneGLSharedDataContext* shared_ = nullptr;
  int rest_id_ = -1;
  std::vector<double> rest_positions_;  // #V by 3 at start
  std::vector<int> example_ids_;
  std::shared_ptr<const ExampleSet> example_set_;
  std::unique_ptr<SolveWorker> worker_;
  std::vector<int> handles_;     // #H vertex indices
  std::vector<double> targets_;  // #H by 3
  std::vector<double> last_weights_;  // #E weights of the pose in the layer (0 at rest)
  std::optional<ScreenProjection> projection_;  // the view of the last frame drawn
  std::optional<Click> pending_click_;
  std::optional<ViewPlaneDrag> drag_;
  bool cold_start_next_ = false;  // set by "Reset pose"
  bool converged_solve_ = false;  // the solve being applied is the end of a drag's (for the log)
  bool layer_has_selection_ = false;  // its selection overlay must follow the vertices
  SolveWorker::Counts drag_start_counts_;
  LatencyStats latency_;
  QPointer<QDockWidget> dock_;
  QPointer<DragDock> panel_;
};

}  // namespace meshik::edit
