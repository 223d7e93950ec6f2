// "MeshIK: Drag to Pose": the MeshLab edit tool. The layer current at the start is the rest mesh,
// the other layers with its vertices and triangles are the examples; click vertices to make them
// handles (each click a group of its own, ctrl+click adds to the last group, a selection made
// before the start is one group), drag a handle and its group follows, R turns a group about its
// centre; the pose is solved on a worker thread (coalescing mouse moves) and written into the rest
// layer on the GUI thread only. The tool keeps the rest positions, handles, undo history and
// keyframes for its whole life: a layer switch, an import or a filter that ends the tool does not
// lose them, and a restart never takes the posed layer as the rest. The thin Qt/GL adapter over
// the GL-free logic in logic/.
#pragma once

#include "drag_dock.h"
#include "group_rotation.h"
#include "keyframe_list.h"
#include "latency_stats.h"
#include "mirror_pairing.h"
#include "pose_state.h"
#include "screen_projection.h"
#include "solve_worker.h"
#include "view_plane_drag.h"

#include <common/plugins/interfaces/edit_plugin.h>

#include <QDockWidget>
#include <QObject>
#include <QPoint>
#include <QPointer>
#include <QUndoStack>

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
  // Another layer became current (clicked, imported): the tool goes on posing its rest layer.
  void layerChanged(MeshDocument& document, MeshModel& old_layer, GLArea* area,
                    MLSceneGLSharedDataContext* shared) override;
  void decorate(MeshModel& layer, GLArea* area, QPainter* painter) override;
  void mousePressEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) override;
  void mouseMoveEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) override;
  void mouseReleaseEvent(QMouseEvent* event, MeshModel& layer, GLArea* area) override;
  void keyPressEvent(QKeyEvent* event, MeshModel& layer, GLArea* area) override;
  void wheelEvent(QWheelEvent* event, MeshModel& layer, GLArea* area) override;

  // Puts `state` back (handles, groups, targets, the pose in the layer, its weights): for undo
  // and redo. `what` says which in the log ("undo drag", ...).
  void restoreState(const PoseState& state, const QString& what);

 protected:
  // Keeps Esc (during a drag or a turn) and the tool's keys from MeshLab's shortcuts.
  bool eventFilter(QObject* watched, QEvent* event) override;

 private slots:
  void applyFinishedPose();  // on the GUI thread, after the worker finished a request
  void rebuildExamples();
  void restartWorker();
  void resetPose();
  void clearHandles();
  void addKeyframe();
  void clearKeyframes();
  void saveConstraintFile();
  void savePose();
  void poseToNewLayer();
  void mirrorModeChanged();  // forgets a picked mirror plane; the view plane comes from the current view

 private:
  struct Click {
    double x, y;     // GL window pixels
    bool remove;     // shift+click
    bool add_to_group;  // ctrl+click
  };
  // A rectangle drawn from an empty spot: its visible vertices become one new group.
  struct Rectangle {
    double x0, y0, x1, y1;  // GL window pixels: the press and the cursor now
  };

  // Ends the interactive part (dock, worker, drag, event filter); the session stays.
  void suspend();
  // Forgets the session (rest positions, handles, history, keyframes).
  void forgetSession();
  // Whether the session can go on with `layer` as its rest layer: same document, the layer still
  // there with the same vertex count, holding the rest pose or the tool's last pose.
  bool canResume(MeshDocument& document) const;
  // Asks for a file to save to (title, suggested name beside the rest mesh's file, filter) once
  // the newest pose is in the layer; empty when cancelled or when the tool is not running.
  QString askSavePath(const QString& title, const QString& file_name, const QString& filter);
  MeshModel* restLayer() const;
  void report(const QString& error);
  void log(const QString& text);
  // Posts the handles' current targets; quick: one Gauss-Newton step (a move during a drag).
  void postSolve(bool quick, Clock::time_point event_time);
  void applyOutcome(const SolveOutcome& outcome);
  void handleClick(const Click& click, MeshModel& layer);
  // In decorate (the depth buffer is the frame's): the visible vertices in the rectangle as a new group.
  void handleRectangle(const Rectangle& rectangle);
  // The rectangle being drawn, in window pixels, as lines over the view.
  void drawRectangle(const Rectangle& rectangle) const;
  void finishPendingSolve();
  // Solves the current targets to convergence and waits for the pose (the end of a drag or turn).
  void convergeNow();
  // Tells MeshLab the layer's positions and normals changed, uploads its GL buffers, refreshes a
  // selection overlay and schedules a repaint; returns the times of these parts (not the copy).
  PoseWriteTimes refreshBuffers(MeshModel& layer);
  // Writes #V by 3 `positions` and their `normals` (the worker's; computed here when empty)
  // into the rest layer, keeps them as last_written_ and updates the GL buffers; returns when it
  // began and what each part took.
  PoseWriteTimes writePose(MeshModel& rest, const std::vector<double>& positions, const SurfaceNormals& normals);
  // A flat-shaded rest layer of many triangles is drawn smooth while the tool runs (see
  // drag_tool_shading.cpp), and gets the artist's shading back at the end.
  void shadeSmoothWhilePosing(MeshModel& rest);
  void restoreArtistShading();
  // How the view draws `layer` (empty without a view), and whether it draws it flat (face normals).
  MLRenderingData viewOf(const MeshModel& layer) const;
  bool drawnFlat(const MeshModel& layer) const;
  std::pair<double, double> glPosition(const QMouseEvent* event) const;
  std::pair<double, double> cursorGlPosition() const;

  // The state now (handles, groups, targets, the layer's positions, weights).
  std::shared_ptr<const PoseState> captureState() const;
  // Pushes one undo step from `before` to the state now, named `text`.
  void pushStep(std::shared_ptr<const PoseState> before, const QString& text);
  void showHandleCount();

  // Symmetry ("Mirror" in the dock): the mirror plane (none when off, or while a plane through a
  // picked vertex waits for its click); the click that picks that plane's vertex (returns whether
  // the click was taken for it); pairing the newest handle with the vertex nearest its mirror
  // image (added as a handle in the mirrored group of its group, else in a group of its own); and
  // moving the partners of the active group's handles to the mirror images of their targets.
  std::optional<MirrorPlane> mirrorPlane() const;
  bool pickMirrorPlane(int vertex);
  void addMirrorPartner();
  void mirrorActiveGroup();

  // Rotation: R starts it (about the group of the handle under the cursor, else of the last one
  // grabbed or added).
  void beginRotation();
  void updateRotation();
  void applyRotation();
  void cancelRotation();
  bool handleRotationKey(QKeyEvent* event);
  void cancelDrag();
  // A mouse move during a drag or a turn: the group's new targets (mirrored) posted to the worker
  // as a quick solve; no repaint (the new pose repaints when it is in the layer).
  void moveHandles(const QMouseEvent* event);
  // Sends a mouse or wheel event to MeshLab's own view navigation (trackball).
  void navigate(QEvent* event);
  QString helpText() const;

  // The session: kept from startEdit to startEdit while canResume holds.
  QPointer<MeshDocument> document_;  // null once MeshLab deletes the document
  int rest_id_ = -1;
  std::vector<double> rest_positions_;  // #V by 3: the rest pose, for the tool's whole life
  std::vector<double> last_written_;    // #V by 3: the pose the tool last wrote into the layer
  std::vector<int> handles_;            // #H vertex indices
  std::vector<int> groups_;             // #H group numbers
  std::vector<double> targets_;         // #H by 3
  std::vector<int> mirrors_;            // #H: the vertex of the handle mirroring each, or -1
  std::vector<double> last_weights_;    // #E weights of the pose in the layer (empty at rest)
  std::vector<int> inverted_;           // triangles the last pose turned inside out
  int active_group_ = 0;                // the group R turns and ctrl+click adds to
  std::optional<MirrorPlane> picked_mirror_plane_;  // through a picked vertex (reset when the option changes)
  std::optional<Direction> view_mirror_normal_;      // the view's vertical plane's, when that option was chosen
  QUndoStack history_;
  KeyframeList keyframes_;

  // The interactive part: from startEdit to endEdit.
  GLArea* area_ = nullptr;
  MLSceneGLSharedDataContext* shared_ = nullptr;
  std::vector<int> example_ids_;
  std::vector<int> triangles_;  // #F by 3: the rest layer's, for the pose's normals
  std::shared_ptr<const ExampleSet> example_set_;
  std::unique_ptr<SolveWorker> worker_;
  std::optional<MLRenderingData> artist_shading_;  // the rest layer's view before it was drawn smooth
  std::optional<std::vector<double>> next_start_weights_;  // the next solve's warm start (after undo, reset)
  std::optional<ScreenProjection> projection_;  // the view of the last frame drawn
  std::optional<Click> pressed_;  // a press on no handle: a click, or the start of a rectangle
  std::optional<Rectangle> rectangle_;  // being drawn (the mouse moved 5 pixels or more)
  std::optional<Click> pending_click_;
  std::optional<Rectangle> pending_rectangle_;
  std::optional<ViewPlaneDrag> drag_;
  std::optional<GroupRotation> rotation_;
  QString typed_degrees_;     // digits typed during a turn
  bool rotation_dragging_ = false;
  std::shared_ptr<const PoseState> step_before_;  // the state when the drag or turn began
  bool navigating_ = false;   // a middle or alt drag goes to MeshLab's trackball
  bool converged_solve_ = false;  // the solve being applied is the end of a drag's (for the log)
  bool layer_has_selection_ = false;  // its selection overlay must follow the vertices
  SolveWorker::Counts drag_start_counts_;
  // Where the newest mouse move of a drag or turn was, on the screen: Qt folds moves queued while
  // the GUI thread is busy into the newest, so the drag ends where the cursor did even when fewer
  // moves arrive than the mouse made.
  QPoint last_move_screen_;
  DragTimings timings_;
  QPointer<QDockWidget> dock_;
  QPointer<DragDock> panel_;
};

}  // namespace meshik::edit
