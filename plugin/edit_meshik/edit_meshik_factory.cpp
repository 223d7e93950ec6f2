#include "edit_meshik_factory.h"

#include "drag_tool.h"

#include <QAction>
#include <QGuiApplication>
#include <QIcon>
#include <QPainter>
#include <QPixmap>

namespace {

// The tool's icon, painted: a bent limb (two segments) with a handle being dragged.
QIcon dragToPoseIcon() {
  QPixmap pixmap(32, 32);
  pixmap.fill(Qt::transparent);
  QPainter painter(&pixmap);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setPen(QPen(QColor(70, 110, 170), 5, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  painter.drawPolyline(QPolygon({QPoint(4, 28), QPoint(13, 15), QPoint(25, 9)}));
  painter.setPen(QPen(QColor(120, 120, 120), 1.5, Qt::DashLine));
  painter.drawLine(QPoint(25, 9), QPoint(27, 24));
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(230, 40, 40));
  painter.drawEllipse(QPointF(25, 9), 4.5, 4.5);
  painter.setBrush(QColor(250, 210, 0));
  painter.drawEllipse(QPointF(4, 28), 3.5, 3.5);
  return QIcon(pixmap);
}

}  // namespace

EditMeshIKFactory::EditMeshIKFactory() {
  drag_to_pose_ = new QAction(QStringLiteral("MeshIK: Drag to Pose"), this);
  // pymeshlab loads plugins in a QCoreApplication, where pixmaps abort and shortcuts warn; it
  // refuses edit plugins anyway, so the icon and the shortcut come only with a GUI.
  if (qobject_cast<QGuiApplication*>(QCoreApplication::instance()) != nullptr) {
    drag_to_pose_->setIcon(dragToPoseIcon());
    drag_to_pose_->setShortcut(QKeySequence(Qt::CTRL + Qt::SHIFT + Qt::Key_M));
  }
  drag_to_pose_->setCheckable(true);
  drag_to_pose_->setToolTip(meshik::edit::DragTool::info());
  actionList.push_back(drag_to_pose_);
}

EditMeshIKFactory::~EditMeshIKFactory() = default;

QString EditMeshIKFactory::pluginName() const { return QStringLiteral("EditMeshIK"); }

QString EditMeshIKFactory::vendor() const { return QStringLiteral("MeshIK"); }

EditTool* EditMeshIKFactory::getEditTool(const QAction* action) {
  return action == drag_to_pose_ ? new meshik::edit::DragTool() : nullptr;
}

QString EditMeshIKFactory::getEditToolDescription(const QAction*) { return meshik::edit::DragTool::info(); }

