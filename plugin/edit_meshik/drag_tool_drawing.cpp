// What the tool draws over the 3D view: the handles (one colour per group, the grabbed group red),
// the centre of a turn, the triangles the pose turned inside out, and the help lines (keys and the
// current mode) on the canvas through MeshLab's realTimeLog.
#include "drag_tool.h"

#include <meshlab/glarea.h>

#include <array>

namespace meshik::edit {
namespace {

// A colour per group number (cycling through 8 that stand out on grey and blue), RGB in [0, 1].
std::array<float, 3> groupColour(int group) {
  static const float kColours[8][3] = {{1.0f, 0.85f, 0.0f}, {0.0f, 0.9f, 0.9f}, {0.9f, 0.3f, 1.0f},
                                       {0.3f, 1.0f, 0.3f},  {1.0f, 0.55f, 0.1f}, {0.4f, 0.6f, 1.0f},
                                       {1.0f, 0.5f, 0.7f},  {0.7f, 1.0f, 0.7f}};
  const float* c = kColours[((group % 8) + 8) % 8];
  return {c[0], c[1], c[2]};
}

}  // namespace

QString DragTool::helpText() const {
  if (rotation_) {
    static const char* kAxisNames[] = {"view axis", "X", "Y", "Z"};
    return QStringLiteral("<b>Turning group %1</b> about the %2%3<br>drag to turn; X/Y/Z lock an axis (again: view axis)"
                          "<br>type degrees, Return applies, Backspace or Esc cancels")
        .arg(active_group_)
        .arg(kAxisNames[static_cast<int>(rotation_->axis())])
        .arg(typed_degrees_.isEmpty() ? QString() : QStringLiteral(": %1 degrees").arg(typed_degrees_));
  }
  if (drag_) return QStringLiteral("<b>Moving group %1</b><br>release to apply, Esc cancels").arg(active_group_);
  if (panel_ && panel_->mirrorPlaneKind() != DragDock::kNoMirror && !mirrorPlane())
    return QStringLiteral("<b>Mirror plane</b>: click the vertex it goes through (the %1 plane)")
        .arg(panel_->mirrorPlaneName());
  return QStringLiteral(
             "<b>Posing</b> (%1 handles, %2 undo steps, %3 frames)"
             "<br>click: handle (new group), ctrl+click: add to the group, shift+click: remove"
             "<br>drag from an empty spot: a group of the rectangle; drag a handle: move its group; R: turn it"
             "<br>Ctrl+Z undo, Ctrl+Shift+Z / Ctrl+Y redo; F add frame; M mirror; S save constraints, P save pose"
             "<br>middle or Alt drag, wheel: view")
      .arg(handles_.size())
      .arg(history_.index())
      .arg(keyframes_.count());
}

void DragTool::decorate(MeshModel&, GLArea* area, QPainter*) {
  MeshModel* rest = restLayer();
  if (rest == nullptr) return;
  realTimeLog(QStringLiteral("MeshIK: Drag to Pose"), rest->shortName(), "%s", qUtf8Printable(helpText()));
  glPushMatrix();
  glMultMatrix(rest->cm.Tr);
  double projection[16], modelview[16];
  GLint viewport[4];
  glGetDoublev(GL_PROJECTION_MATRIX, projection);
  glGetDoublev(GL_MODELVIEW_MATRIX, modelview);
  glGetIntegerv(GL_VIEWPORT, viewport);
  projection_.emplace(projection, modelview, viewport);
  if (pending_click_) {
    const Click click = *pending_click_;
    pending_click_.reset();
    handleClick(click, *rest);
  }
  if (pending_rectangle_) {
    const Rectangle rectangle = *pending_rectangle_;
    pending_rectangle_.reset();
    handleRectangle(rectangle);
  }
  glPushAttrib(GL_ENABLE_BIT | GL_POINT_BIT | GL_CURRENT_BIT | GL_POLYGON_BIT);
  glDisable(GL_LIGHTING);
  // The inverted triangles in red on the surface.
  if (!inverted_.empty() && static_cast<size_t>(rest->cm.fn) == rest->cm.face.size()) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -1.0f);
    glColor3f(0.9f, 0.05f, 0.05f);
    glBegin(GL_TRIANGLES);
    for (int f : inverted_)
      if (f >= 0 && f < rest->cm.fn)
        for (int corner = 0; corner < 3; ++corner) glVertex(rest->cm.face[f].cP(corner));
    glEnd();
  }
  // The handles' targets as points over the mesh: the moving or turning group red.
  glDisable(GL_DEPTH_TEST);
  glPointSize(9.0f * static_cast<float>(area->devicePixelRatioF()));
  glBegin(GL_POINTS);
  for (size_t h = 0; h < handles_.size(); ++h) {
    if ((drag_ || rotation_) && groups_[h] == active_group_) {
      glColor3f(1.0f, 0.1f, 0.1f);
    } else {
      const std::array<float, 3> c = groupColour(groups_[h]);
      glColor3f(c[0], c[1], c[2]);
    }
    glVertex3d(targets_[3 * h], targets_[3 * h + 1], targets_[3 * h + 2]);
  }
  if (rotation_) {  // the centre of the turn, white
    glColor3f(1.0f, 1.0f, 1.0f);
    glVertex3d(rotation_->centre()[0], rotation_->centre()[1], rotation_->centre()[2]);
  }
  glEnd();
  if (rectangle_) drawRectangle(*rectangle_);
  glPopAttrib();
  glPopMatrix();
}

void DragTool::drawRectangle(const Rectangle& rectangle) const {
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glLoadIdentity();
  glOrtho(viewport[0], viewport[0] + viewport[2], viewport[1], viewport[1] + viewport[3], -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  glLoadIdentity();
  glColor3f(1.0f, 1.0f, 1.0f);
  glBegin(GL_LINE_LOOP);
  glVertex2d(rectangle.x0, rectangle.y0);
  glVertex2d(rectangle.x1, rectangle.y0);
  glVertex2d(rectangle.x1, rectangle.y1);
  glVertex2d(rectangle.x0, rectangle.y1);
  glEnd();
  glPopMatrix();
  glMatrixMode(GL_PROJECTION);
  glPopMatrix();
  glMatrixMode(GL_MODELVIEW);
}

}  // namespace meshik::edit
