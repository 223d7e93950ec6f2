// The MeshLab filter plugin "filter_meshik": Mesh-Based Inverse Kinematics (Sumner et al. 2005)
// for MeshLab 2025.07 and pymeshlab 2025.7. Two filters, each a thin adapter from the
// MeshDocument's layers to the MeshIK core:
//   "MeshIK: Pose from Examples" (compute_coord_meshik_pose)   pose_filter.h
//   "MeshIK: Blend Examples"     (compute_coord_meshik_blend)  blend_filter.h
// Every error reaches the host as an MLException (the MeshLab GUI shows it in a dialog, pymeshlab
// raises PyMeshLabException): nothing else escapes applyFilter.
#pragma once

#include "solver_cache.h"

#include <common/plugins/interfaces/filter_plugin.h>

#include <QObject>

class FilterMeshIKPlugin : public QObject, public FilterPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
  Q_INTERFACES(FilterPlugin)

 public:
  enum { FP_MESHIK_POSE, FP_MESHIK_BLEND };

  FilterMeshIKPlugin();

  QString pluginName() const override;
  QString vendor() const override;
  QString filterName(ActionIDType filter) const override;
  QString pythonFilterName(ActionIDType filter) const override;
  QString filterInfo(ActionIDType filter) const override;
  FilterClass getClass(const QAction* action) const override;
  FilterArity filterArity(const QAction* action) const override;
  int getPreConditions(const QAction* action) const override;
  int postCondition(const QAction* action) const override;
  RichParameterList initParameterList(const QAction* action, const MeshDocument& document) override;
  std::map<std::string, QVariant> applyFilter(const QAction* action, const RichParameterList& parameters,
                                              MeshDocument& document, unsigned int& post_condition_mask,
                                              vcg::CallBackPos* callback) override;

 private:
  meshik::plugin::SolverCache cache_;  // the last example set and factorization, reused by re-runs
};
