#include "drag_dock.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace meshik::edit {
namespace {

// A push button that emits `signal` of `dock` when clicked.
template <typename Signal>
QPushButton* commandButton(DragDock* dock, const QString& text, const QString& tip, Signal signal) {
  auto* button = new QPushButton(text, dock);
  button->setToolTip(tip);
  QObject::connect(button, &QPushButton::clicked, dock, signal);
  return button;
}

}  // namespace

DragDock::DragDock(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(new QLabel(tr("<b>Click</b> a vertex: add a handle; <b>Shift+click</b>: remove it; "
                                  "<b>drag</b> a handle to pose. Keys: S save constraint file, P save pose, "
                                  "R reset, C clear."),
                               this));
  static_cast<QLabel*>(layout->itemAt(0)->widget())->setWordWrap(true);

  layout->addWidget(new QLabel(tr("Example layers"), this));
  examples_ = new QListWidget(this);
  examples_->setMaximumHeight(110);
  layout->addWidget(examples_);
  connect(examples_, &QListWidget::itemChanged, this, &DragDock::examplesChanged);

  auto* form = new QFormLayout();
  feature_space_ = new QComboBox(this);
  feature_space_->addItems({tr("Nonlinear"), tr("Linear")});
  form->addRow(tr("Feature space"), feature_space_);
  regularization_ = new QDoubleSpinBox(this);
  regularization_->setRange(0.0, 1000.0);
  regularization_->setDecimals(4);
  regularization_->setSingleStep(0.01);
  form->addRow(tr("Weight regularization"), regularization_);
  layout->addLayout(form);
  connect(feature_space_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &DragDock::optionsChanged);
  connect(regularization_, &QDoubleSpinBox::editingFinished, this, &DragDock::optionsChanged);

  layout->addWidget(new QLabel(tr("Weights"), this));
  weight_bars_ = new QVBoxLayout();
  layout->addLayout(weight_bars_);
  handles_ = new QLabel(this);
  solve_ = new QLabel(this);
  latency_ = new QLabel(this);
  error_ = new QLabel(this);
  error_->setStyleSheet("color: #c00000");
  error_->setWordWrap(true);
  latency_->setWordWrap(true);
  for (QLabel* label : {handles_, solve_, latency_, error_}) layout->addWidget(label);

  layout->addWidget(commandButton(this, tr("Reset pose"), tr("Handles back to their rest positions (R)"),
                                  &DragDock::resetPose));
  layout->addWidget(commandButton(this, tr("Clear handles"), tr("Remove every handle (C)"), &DragDock::clearHandles));
  layout->addWidget(commandButton(this, tr("Save constraint file..."),
                                  tr("The handles and their targets as one frame of a meshik-constraints file (S)"),
                                  &DragDock::saveConstraintFile));
  layout->addWidget(commandButton(this, tr("Save pose..."), tr("Save the posed layer to a mesh file (P)"),
                                  &DragDock::savePose));
  layout->addWidget(commandButton(this, tr("Pose into a new layer"),
                                  tr("Copy the current pose into a new layer \"MeshIK pose of ...\" (N)"),
                                  &DragDock::poseToNewLayer));
  layout->addStretch(1);
  showHandles(0);
}

void DragDock::setExampleLayers(const std::vector<std::pair<QString, int>>& layers) {
  const QSignalBlocker block(examples_);
  examples_->clear();
  for (const auto& [label, id] : layers) {
    auto* item = new QListWidgetItem(label, examples_);
    item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
    item->setCheckState(Qt::Checked);
    item->setData(Qt::UserRole, id);
  }
}

std::vector<int> DragDock::checkedExampleLayers() const {
  std::vector<int> ids;
  for (int i = 0; i < examples_->count(); ++i)
    if (examples_->item(i)->checkState() == Qt::Checked) ids.push_back(examples_->item(i)->data(Qt::UserRole).toInt());
  return ids;
}

bool DragDock::linearFeatureSpace() const { return feature_space_->currentIndex() == 1; }

double DragDock::weightRegularization() const { return regularization_->value(); }

void DragDock::showPose(const std::vector<double>& weights, int iterations, double solve_ms, int inverted_triangles) {
  while (weight_bars_->count() > static_cast<int>(weights.size())) delete weight_bars_->takeAt(0)->widget();
  while (weight_bars_->count() < static_cast<int>(weights.size())) {
    auto* bar = new QProgressBar(this);
    bar->setRange(0, 1000);
    bar->setMaximumHeight(16);
    weight_bars_->addWidget(bar);
  }
  for (size_t i = 0; i < weights.size(); ++i) {
    auto* bar = static_cast<QProgressBar*>(weight_bars_->itemAt(static_cast<int>(i))->widget());
    bar->setValue(static_cast<int>(std::lround(1000.0 * std::clamp(std::abs(weights[i]), 0.0, 1.0))));
    bar->setFormat(QString::number(weights[i], 'f', 3));
  }
  solve_->setText(tr("%1 iterations, solve %2 ms, %3 inverted triangles")
                      .arg(iterations)
                      .arg(solve_ms, 0, 'f', 1)
                      .arg(inverted_triangles));
}

void DragDock::showHandles(int count) { handles_->setText(tr("%1 handles").arg(count)); }

void DragDock::showLatency(const QString& text) { latency_->setText(text); }

void DragDock::showError(const QString& text) { error_->setText(text); }

}  // namespace meshik::edit
