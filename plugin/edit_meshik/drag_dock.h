// The floating panel of "MeshIK: Drag to Pose": example layers, options, the last solve's
// readout (weights as bars, iterations, solve time, inverted triangles, drag latency), errors,
// and the commands. Widgets only: the tool (drag_tool.h) does the work on its signals.
#pragma once

#include <QString>
#include <QWidget>

#include <vector>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QVBoxLayout;

namespace meshik::edit {

class DragDock : public QWidget {
  Q_OBJECT

 public:
  explicit DragDock(QWidget* parent);

  // The candidate example layers (label and id), all checked; emits nothing.
  void setExampleLayers(const std::vector<std::pair<QString, int>>& layers);
  // The ids of the checked example layers.
  std::vector<int> checkedExampleLayers() const;
  bool linearFeatureSpace() const;
  double weightRegularization() const;

  // The readout of a finished pose: #E weights, Gauss-Newton iterations, solve time, inverted faces.
  void showPose(const std::vector<double>& weights, int iterations, double solve_ms, int inverted_triangles);
  void showHandles(int count);
  void showLatency(const QString& text);
  // An error in red (empty: none).
  void showError(const QString& text);

 signals:
  void examplesChanged();
  void optionsChanged();
  void resetPose();
  void clearHandles();
  void saveConstraintFile();
  void savePose();
  void poseToNewLayer();

 private:
  QListWidget* examples_;
  QComboBox* feature_space_;
  QDoubleSpinBox* regularization_;
  QVBoxLayout* weight_bars_;
  QLabel* handles_;
  QLabel* solve_;
  QLabel* latency_;
  QLabel* error_;
};

}  // namespace meshik::edit
