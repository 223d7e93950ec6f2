#include "drag_dock.h"

#include "meshik/meshik.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace meshik::edit {
namespace {

constexpr int kWidth = 320;         // the panel's fixed width: long lines wrap, never widen it
constexpr int kMaxWeightBars = 12;  // bars shown (a set with more examples shows the first ones)
constexpr double kExtrapolation = 0.05;  // weights beyond [-this, 1 + this] extrapolate

// A push button that emits `signal` of `dock` when clicked.
template <typename Signal>
QPushButton* commandButton(DragDock* dock, const QString& text, const QString& tip, Signal signal) {
  auto* button = new QPushButton(text, dock);
  button->setToolTip(tip);
  QObject::connect(button, &QPushButton::clicked, dock, signal);
  return button;
}

// A wrapping label of fixed height (`lines` text lines), so the widgets below never move.
QLabel* fixedLabel(QWidget* parent, int lines) {
  auto* label = new QLabel(parent);
  label->setWordWrap(true);
  label->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  label->setFixedHeight(lines * label->fontMetrics().lineSpacing() + 4);
  return label;
}

// A spin box for a number in [0, maximum] shown with 4 decimals, stepping by `step`, starting at `value`.
QDoubleSpinBox* numberBox(QWidget* parent, double maximum, double step, double value, const QString& tip) {
  auto* box = new QDoubleSpinBox(parent);
  box->setRange(0.0, maximum);
  box->setDecimals(4);
  box->setSingleStep(step);
  box->setValue(value);
  if (!tip.isEmpty()) box->setToolTip(tip);
  return box;
}

}  // namespace

DragDock::DragDock(QWidget* parent) : QWidget(parent) {
  setFixedWidth(kWidth);
  auto* layout = new QVBoxLayout(this);
  auto* help = new QLabel(tr("<b>Click</b> a vertex: a handle (ctrl: into the last group; shift: remove). "
                             "<b>Drag</b> a handle: move its group; <b>R</b>: turn it. Ctrl+Z undo, "
                             "Ctrl+Shift+Z redo, F add frame, S save constraints, P save pose."),
                          this);
  help->setWordWrap(true);
  layout->addWidget(help);

  // The commands first, in a grid (two per row) that nothing below can shift.
  struct Command {
    QString text, tip;
    void (DragDock::*signal)();
  };
  const Command kCommands[] = {
      {tr("Save constraints..."),
       tr("The handle groups and the frames (or the targets now, as one frame) as a meshik-constraints file (S)"),
       &DragDock::saveConstraintFile},
      {tr("Save pose..."), tr("Save the posed layer to a mesh file (P)"), &DragDock::savePose},
      {tr("Add frame"), tr("Append the targets now as the next frame (F)"), &DragDock::addKeyframe},
      {tr("Clear frames"), tr("Forget the frames added so far"), &DragDock::clearKeyframes},
      {tr("Pose into a new layer"), tr("Copy the current pose into a new layer \"MeshIK pose of ...\" (N)"),
       &DragDock::poseToNewLayer},
      {tr("Clear handles"), tr("Remove every handle (undo: Ctrl+Z)"), &DragDock::clearHandles},
      {QString(), QString(), nullptr},  // an empty cell: Reset sits apart from the other commands
      {tr("Reset pose"), tr("Handles and mesh back to the rest pose (undo: Ctrl+Z)"), &DragDock::resetPose},
  };
  auto* commands = new QGridLayout();
  int cell = 0;
  for (const Command& command : kCommands) {
    if (command.signal)
      commands->addWidget(commandButton(this, command.text, command.tip, command.signal), cell / 2, cell % 2);
    ++cell;
  }
  layout->addLayout(commands);

  layout->addWidget(new QLabel(tr("Example layers"), this));
  examples_ = new QListWidget(this);
  examples_->setFixedHeight(90);
  layout->addWidget(examples_);
  connect(examples_, &QListWidget::itemChanged, this, &DragDock::examplesChanged);

  auto* form = new QFormLayout();
  feature_space_ = new QComboBox(this);
  feature_space_->addItems({tr("Nonlinear"), tr("Linear")});
  form->addRow(tr("Feature space"), feature_space_);
  regularization_ = numberBox(this, 1000.0, 0.01, 0.0, QString());
  form->addRow(tr("Weight regularization"), regularization_);
  blend_ = new QComboBox(this);
  blend_->addItems({tr("Affine"), tr("Free")});
  blend_->setToolTip(tr("Stretch blend: affine I + sum w (S - I), or the paper's free sum w S"));
  form->addRow(tr("Stretch blend"), blend_);
  regions_ = new QSpinBox(this);
  regions_->setRange(0, 8);
  regions_->setValue(1);
  regions_->setSpecialValueText(tr("Automatic"));
  regions_->setToolTip(tr("Regions of the surface with their own example weights (1: one set of weights)"));
  form->addRow(tr("Regions"), regions_);
  region_smoothness_ =
      numberBox(this, 1000.0, 0.01, 0.01, tr("How strongly neighbouring regions' weights are pulled together"));
  form->addRow(tr("Region smoothness"), region_smoothness_);
  handle_stiffness_ = numberBox(this, 1e6, 0.1, 0.0,
                                tr("Hard: each handle exactly at its target. A stiffness > 0 makes the handles soft: "
                                   "a target out of the examples' reach bends the region instead of pulling one "
                                   "vertex into a spike (small: loose, large: nearly hard)"));
  handle_stiffness_->setSpecialValueText(tr("Hard"));
  form->addRow(tr("Handle stiffness"), handle_stiffness_);
  mirror_ = new QComboBox(this);
  mirror_->addItems({tr("Off"), tr("X (plane x = centre)"), tr("Y (plane y = centre)"), tr("Z (plane z = centre)"),
                     tr("X (plane through a picked vertex)"), tr("Y (plane through a picked vertex)"),
                     tr("Z (plane through a picked vertex)"), tr("View's vertical plane (through the centre)"),
                     tr("View's vertical plane (through a picked vertex)")});
  mirror_->setToolTip(tr("New handles get a partner at the vertex nearest their mirror image (within 1% of the "
                         "diagonal); moves and turns are mirrored. With a picked plane, the next click places "
                         "the plane through the clicked vertex. The view's vertical plane contains the view "
                         "direction and the view's up vector (it swaps left and right on the screen); it is "
                         "taken from the view when chosen and stays fixed when the view turns"));
  form->addRow(tr("Mirror"), mirror_);
  layout->addLayout(form);
  connect(feature_space_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &DragDock::optionsChanged);
  connect(regularization_, &QDoubleSpinBox::editingFinished, this, &DragDock::optionsChanged);
  connect(blend_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &DragDock::optionsChanged);
  connect(regions_, &QSpinBox::editingFinished, this, &DragDock::optionsChanged);
  connect(region_smoothness_, &QDoubleSpinBox::editingFinished, this, &DragDock::optionsChanged);
  connect(handle_stiffness_, &QDoubleSpinBox::editingFinished, this, &DragDock::optionsChanged);
  connect(mirror_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &DragDock::mirrorChanged);

  handles_ = fixedLabel(this, 1);
  keyframes_ = fixedLabel(this, 1);
  solve_ = fixedLabel(this, 1);
  latency_ = fixedLabel(this, 4);
  error_ = fixedLabel(this, 3);
  error_->setStyleSheet("color: #c00000");
  for (QLabel* label : {handles_, keyframes_, solve_, latency_, error_}) layout->addWidget(label);

  layout->addWidget(new QLabel(tr("Weights (red: negative; orange: past the examples)"), this));
  for (int i = 0; i < kMaxWeightBars; ++i) {
    auto* bar = new QProgressBar(this);
    bar->setRange(0, 1000);
    bar->setFixedHeight(16);
    bar->setVisible(false);
    layout->addWidget(bar);
    weight_bars_.push_back(bar);
  }
  extrapolation_ = fixedLabel(this, 2);
  extrapolation_->setStyleSheet("color: #b05000");
  layout->addWidget(extrapolation_);
  layout->addStretch(1);
  showHandles(0, 0);
  showKeyframes(0);
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

void DragDock::setWeightNames(const std::vector<QString>& names) { weight_names_ = names; }

bool DragDock::linearFeatureSpace() const { return feature_space_->currentIndex() == 1; }

// The "Mirror" entries: 0 off; 1-3 X, Y, Z through the centre; 4-6 through a picked vertex; 7, 8 the
// view's vertical plane through the centre, through a picked vertex.
int DragDock::mirrorPlaneKind() const {
  const int index = mirror_->currentIndex();
  if (index <= 0) return kNoMirror;
  return index >= 7 ? kViewMirror : (index - 1) % 3;
}

QString DragDock::mirrorPlaneName() const {
  const int kind = mirrorPlaneKind();
  if (kind == kNoMirror) return QString();
  return kind == kViewMirror ? QStringLiteral("view's vertical") : QString(QChar("XYZ"[kind]));
}

bool DragDock::mirrorThroughPickedVertex() const {
  const int index = mirror_->currentIndex();
  return (index >= 4 && index <= 6) || index == 8;
}

QString DragDock::cycleMirror() {
  mirror_->setCurrentIndex((mirror_->currentIndex() + 1) % mirror_->count());
  return mirror_->currentText();
}

double DragDock::weightRegularization() const { return regularization_->value(); }

bool DragDock::freeBlend() const { return blend_->currentIndex() == 1; }

int DragDock::regionCount() const { return regions_->value() == 0 ? kAutomaticRegions : regions_->value(); }

double DragDock::regionSmoothness() const { return region_smoothness_->value(); }
double DragDock::handleStiffness() const { return handle_stiffness_->value(); }

void DragDock::showPose(const std::vector<double>& weights, int iterations, double solve_ms, int inverted_triangles) {
  QStringList past;
  for (size_t i = 0; i < weight_bars_.size(); ++i) {
    QProgressBar* bar = weight_bars_[i];
    bar->setVisible(i < weights.size());
    if (i >= weights.size()) continue;
    const double w = weights[i];
    const size_t examples = weight_names_.size();
    QString name = examples ? weight_names_[i % examples] : QString::number(i + 1);
    if (examples && weights.size() > examples) name += tr(" (region %1)").arg(i / examples + 1);
    bar->setValue(static_cast<int>(std::lround(1000.0 * std::clamp(std::abs(w), 0.0, 1.0))));
    bar->setFormat(name + QString::asprintf("  %+.3f", w));
    const bool beyond = w < -kExtrapolation || w > 1.0 + kExtrapolation;
    bar->setStyleSheet(w < 0.0 ? QStringLiteral("QProgressBar::chunk { background: #d04040; }")
                       : beyond ? QStringLiteral("QProgressBar::chunk { background: #e08000; }")
                                : QString());
    if (beyond) past << QStringLiteral("%1 %2").arg(name).arg(w, 0, 'f', 2);
  }
  extrapolation_->setText(past.isEmpty() ? QString()
                                         : tr("Extrapolating past the examples: %1").arg(past.join(", ")));
  solve_->setText(tr("%1 iterations, solve %2 ms, %3 inverted triangles (red)")
                      .arg(iterations)
                      .arg(solve_ms, 0, 'f', 1)
                      .arg(inverted_triangles));
}

void DragDock::showHandles(int count, int groups) {
  handles_->setText(tr("%1 handles in %2 groups").arg(count).arg(groups));
}

void DragDock::showKeyframes(int count) { keyframes_->setText(tr("%1 frames").arg(count)); }

void DragDock::showLatency(const QString& text) { latency_->setText(text); }

void DragDock::showError(const QString& text) { error_->setText(text); }

}  // namespace meshik::edit
