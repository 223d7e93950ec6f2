// The MeshLab edit plugin "edit_meshik": one action, "MeshIK: Drag to Pose" (Edit menu and
// toolbar, Ctrl+Shift+M), whose tool is drag_tool.h. Its own .so beside filter_meshik: an edit
// plugin implements another MeshLab interface (IID) than a filter plugin.
#pragma once

#include <common/plugins/interfaces/edit_plugin.h>

#include <QObject>

namespace meshik::edit {
class DragTool;
}

class EditMeshIKFactory : public QObject, public EditPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(EDIT_PLUGIN_IID)
  Q_INTERFACES(EditPlugin)

 public:
  EditMeshIKFactory();
  ~EditMeshIKFactory() override;

  QString pluginName() const override;
  QString vendor() const override;
  EditTool* getEditTool(const QAction* action) override;
  QString getEditToolDescription(const QAction* action) override;

 private:
  QAction* drag_to_pose_;
};
