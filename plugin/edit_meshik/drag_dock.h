// The floating panel of "MeshIK: Drag to Pose": the commands first (their places never change),
// then example layers, options, and the last solve's readout (weights as bars named after their
// example layers, with their sign; a warning when they extrapolate past the examples; iterations,
// solve time, inverted triangles, drag latency), the keyframe count, errors. Widgets only: the tool
// (drag_tool.h) does the work on its signals.
#pragma once

#include <QString>
#include <QWidget>

#include <vector>

class QComboBox;
class QDoubleSpinBox;
class QSpinBox;
class QLabel;
class QListWidget;
class QProgressBar;

namespace meshik::edit {

class DragDock : public QWidget {
  Q_OBJECT

 public:
  explicit DragDock(QWidget* parent);

  // The candidate example layers (label and id), all checked; emits nothing.
  void setExampleLayers(const std::vector<std::pair<QString, int>>& layers);
  // The ids of the checked example layers.
  std::vector<int> checkedExampleLayers() const;
  // The names of the #E weights the next showPose shows (the example layers' labels).
  void setWeightNames(const std::vector<QString>& names);
  bool linearFeatureSpace() const;
  // The "Mirror" option's plane: kNoMirror (off), 0, 1, 2 (the plane normal to X, Y, Z) or
  // kViewMirror (the view's vertical plane, taken from the view when the option is chosen).
  static constexpr int kNoMirror = -1;
  static constexpr int kViewMirror = 3;
  int mirrorPlaneKind() const;
  // The plane's name for messages: "X", "Y", "Z" or "view's vertical" (empty when off).
  QString mirrorPlaneName() const;
  // Whether the mirror plane goes through a vertex the user picks (else through the rest mesh's
  // centre).
  bool mirrorThroughPickedVertex() const;
  // Steps the "Mirror" option to the next choice (off, X, Y, Z through the centre, X, Y, Z through
  // a picked vertex, the view's vertical plane through the centre, through a picked vertex, off,
  // ...); returns its text.
  QString cycleMirror();
  double weightRegularization() const;
  // The "Stretch blend" option: true for the paper's free weights, false for the affine space.
  bool freeBlend() const;
  // The "Regions" option: a count >= 1 (1: one weight vector), or meshik::kAutomaticRegions.
  int regionCount() const;
  double regionSmoothness() const;
  // The "Handle stiffness" option: 0 for hard handles, > 0 for soft ones (SolverOptions).
  double handleStiffness() const;

  // The readout of a finished pose: #E weights, Gauss-Newton iterations, solve time, inverted faces.
  void showPose(const std::vector<double>& weights, int iterations, double solve_ms, int inverted_triangles);
  void showHandles(int count, int groups);
  void showKeyframes(int count);
  void showLatency(const QString& text);
  // An error in red (empty: none).
  void showError(const QString& text);

 signals:
  void examplesChanged();
  void optionsChanged();
  void mirrorChanged();
  void resetPose();
  void clearHandles();
  void addKeyframe();
  void clearKeyframes();
  void saveConstraintFile();
  void savePose();
  void poseToNewLayer();

 private:
  QListWidget* examples_;
  QComboBox* feature_space_;
  QComboBox* mirror_;
  QDoubleSpinBox* regularization_;
  QComboBox* blend_;
  QSpinBox* regions_;
  QDoubleSpinBox* region_smoothness_;
  QDoubleSpinBox* handle_stiffness_;
  std::vector<QProgressBar*> weight_bars_;  // a fixed number, hidden when unused
  std::vector<QString> weight_names_;
  QLabel* extrapolation_;
  QLabel* handles_;
  QLabel* solve_;
  QLabel* latency_;
  QLabel* keyframes_;
  QLabel* error_;
};

}  // namespace meshik::edit
