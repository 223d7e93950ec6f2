#include "filter_meshik.h"

#include "blend_filter.h"
#include "pose_filter.h"

#include <common/mlexception.h>

namespace {

const char* const kReference =
    "<br><br>See: <i>Robert W. Sumner, Matthias Zwicker, Craig Gotsman, Jovan Popovi&#263;</i><br>"
    "<b>\"Mesh-Based Inverse Kinematics\"</b><br>"
    "ACM Transactions on Graphics 24(3) (SIGGRAPH 2005), 488-495.";

const char* const kPoseInfo =
    "Poses the current layer (the rest mesh) from a few handle vertices, staying within the space "
    "of the example poses (the other layers with the same vertices and triangles). The handles are "
    "the selected vertices of the current layer; their targets come from a target layer (a copy of "
    "the rest mesh with the handles moved), a frame of a MeshIK constraint file, or a 4x4 transform. "
    "The result is written to a new layer (or in place) and the filter returns the example weights, "
    "the Gauss-Newton iterations and the final residual. Running it again with the same rest "
    "layer, examples and handles reuses the factorization: only the solve is repeated.";

const char* const kBlendInfo =
    "Blends the example layers of the current layer (the rest mesh) with the given weights, in "
    "MeshIK's nonlinear feature space (rotations and stretches of every triangle blended "
    "separately) or linearly, without handles: the result is the pose the weights describe, in a "
    "new layer.";

}  // namespace

FilterMeshIKPlugin::FilterMeshIKPlugin() {
  typeList = {FP_MESHIK_POSE, FP_MESHIK_BLEND};
  for (ActionIDType id : types()) actionList.push_back(new QAction(filterName(id), this));
}

QString FilterMeshIKPlugin::pluginName() const { return QStringLiteral("FilterMeshIK"); }

QString FilterMeshIKPlugin::vendor() const { return QStringLiteral("MeshIK"); }

QString FilterMeshIKPlugin::filterName(ActionIDType filter) const {
  switch (filter) {
    case FP_MESHIK_POSE: return QStringLiteral("MeshIK: Pose from Examples");
    case FP_MESHIK_BLEND: return QStringLiteral("MeshIK: Blend Examples");
    default: return QString();
  }
}

QString FilterMeshIKPlugin::pythonFilterName(ActionIDType filter) const {
  switch (filter) {
    case FP_MESHIK_POSE: return QStringLiteral("compute_coord_meshik_pose");
    case FP_MESHIK_BLEND: return QStringLiteral("compute_coord_meshik_blend");
    default: return QString();
  }
}

QString FilterMeshIKPlugin::filterInfo(ActionIDType filter) const {
  switch (filter) {
    case FP_MESHIK_POSE: return QString(kPoseInfo) + kReference;
    case FP_MESHIK_BLEND: return QString(kBlendInfo) + kReference;
    default: return QString();
  }
}

FilterPlugin::FilterClass FilterMeshIKPlugin::getClass(const QAction*) const {
  return FilterPlugin::Smoothing;
}

FilterPlugin::FilterArity FilterMeshIKPlugin::filterArity(const QAction*) const {
  return FilterPlugin::FIXED;
}

int FilterMeshIKPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_FACENUMBER; }

int FilterMeshIKPlugin::postCondition(const QAction*) const {
  return MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_FACENORMAL;
}

RichParameterList FilterMeshIKPlugin::initParameterList(const QAction* action, const MeshDocument& document) {
  switch (ID(action)) {
    case FP_MESHIK_POSE: return meshik::plugin::poseParameters(document);
    case FP_MESHIK_BLEND: return meshik::plugin::blendParameters(document);
    default: wrongActionCalled(action);
  }
  return RichParameterList();
}

std::map<std::string, QVariant> FilterMeshIKPlugin::applyFilter(const QAction* action,
                                                                const RichParameterList& parameters,
                                                                MeshDocument& document, unsigned int&,
                                                                vcg::CallBackPos* callback) {
  const meshik::plugin::Logger logger = [this](const QString& line) { log(line.toStdString()); };
  // The MeshLab GUI catches only MLException (and bad_alloc): translate everything else.
  try {
    switch (ID(action)) {
      case FP_MESHIK_POSE: return meshik::plugin::applyPose(parameters, document, callback, cache_, logger);
      case FP_MESHIK_BLEND: return meshik::plugin::applyBlend(parameters, document, callback, cache_, logger);
      default: wrongActionCalled(action);
    }
  } catch (const MLException&) {
    throw;
  } catch (const meshik::Cancelled&) {
    throw MLException("cancelled");
  } catch (const std::exception& error) {
    throw MLException(QString::fromUtf8(error.what()));
  } catch (...) {
    throw MLException("unexpected error (not a std::exception)");
  }
  return {};
}
