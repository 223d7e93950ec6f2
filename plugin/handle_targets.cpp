#include "handle_targets.h"

#include "layer_arrays.h"

#include <common/mlexception.h>
#include <common/parameters/rich_parameters.h>

#include <QFileInfo>

#include <algorithm>
#include <numeric>

namespace meshik::plugin {

void addHandleTargetParameters(RichParameterList& parameters, const MeshDocument& document) {
  parameters.addParam(RichEnum(
      "targetsource", 0, QStringList{"Target layer", "Constraint file", "Handle transform"},
      "Handle targets from",
      "Where the handles' target positions come from. <b>Target layer</b>: the handles (the selected "
      "vertices of the current layer) go to their positions in the target layer. <b>Constraint file</b>: "
      "the handles and targets of one frame of a MeshIK constraint file (when vertices are selected, "
      "only those of the file's handles). <b>Handle transform</b>: the handles are moved by the 4x4 "
      "handle transform."));
  const MeshModel* current = document.mm();
  parameters.addParam(RichMesh(
      "targetmesh", current != nullptr ? current->id() : 0, &document, "Target layer",
      "With targets from a target layer: the layer holding the handles' target positions (a copy of the "
      "rest mesh with the handle vertices moved); it must have the rest layer's vertex count."));
  parameters.addParam(RichFileOpen(
      "constraintfile", "", QStringList{"*.json"}, "Constraint file",
      "With targets from a constraint file: a MeshIK constraint file (JSON, format \"meshik-constraints\", "
      "version 1; see the MeshIK README). Its handle groups are resolved on the rest layer; its solver "
      "options are used where a parameter says \"from the constraint file\" (the defaults); its rest and "
      "example file names are not used."));
  parameters.addParam(RichString(
      "frame", "0", "Frame",
      "With targets from a constraint file: the frame to pose, by name (e.g. \"0003\") or else by "
      "0-based index. A handle group that the frame does not move keeps its targets of the previous "
      "frames (its rest positions before the first frame that moves it)."));
  parameters.addParam(RichMatrix44(
      "handletransform", Matrix44m::Identity(), "Handle transform",
      "With targets from the handle transform: the 4x4 affine matrix (last row 0 0 0 1) applied to the "
      "rest positions of the handles (the selected vertices), in the layer's own coordinates."));
}

MeshModel* targetLayer(const RichParameterList& parameters, MeshDocument& document, const MeshModel& rest) {
  if (static_cast<TargetSource>(parameters.getEnum("targetsource")) != TargetSource::kTargetLayer)
    return nullptr;
  const unsigned id = parameters.getMeshId("targetmesh");
  MeshModel* target = document.getMesh(id);
  if (target == nullptr) throw MLException(QStringLiteral("targetmesh: there is no layer %1").arg(id));
  compactLayer(*target);
  if (target->cm.vn != rest.cm.vn)
    throw MLException(
        QStringLiteral("targetmesh: the target layer %1 has %2 vertices, the rest layer %3 has %4")
            .arg(describeLayer(*target))
            .arg(target->cm.vn)
            .arg(describeLayer(rest))
            .arg(rest.cm.vn));
  return target;
}

namespace {

// The rest layer's selected vertices; throws when there is none.
std::vector<int> selectedHandles(const MeshModel& rest) {
  std::vector<int> selected = selectedVertices(rest);
  if (selected.empty())
    throw MLException("no vertex is selected on the rest layer " + describeLayer(rest) +
                      ": select the handle vertices (or take the handles from a constraint file)");
  return selected;
}

// #H by 3 targets: the handles' rest positions moved by the affine 4x4 matrix.
std::vector<double> transformedTargets(const Matrix44m& m, const std::vector<int>& handles,
                                       const std::vector<double>& rest_positions) {
  for (int j = 0; j < 4; ++j)
    if (double(m.ElementAt(3, j)) != (j == 3 ? 1.0 : 0.0))
      throw MLException("handletransform: the last row must be 0 0 0 1 (an affine transform)");
  std::vector<double> targets;
  for (int v : handles) {
    const double* p = &rest_positions[3 * v];
    for (int k = 0; k < 3; ++k)
      targets.push_back(double(m.ElementAt(k, 0)) * p[0] + double(m.ElementAt(k, 1)) * p[1] +
                        double(m.ElementAt(k, 2)) * p[2] + double(m.ElementAt(k, 3)));
  }
  return targets;
}

// The file's handles and targets, or only the selected ones among them when some are selected.
HandleTargets constraintFileTargets(const RichParameterList& parameters, const MeshModel& rest,
                                    const std::vector<double>& rest_positions) {
  const QString path = parameters.getOpenFileName("constraintfile");
  if (path.trimmed().isEmpty()) throw MLException("constraintfile: no constraint file given");
  const ConstraintFrame frame =
      readConstraintFrame(path, parameters.getString("frame"), rest_positions.data(),
                          static_cast<int>(rest_positions.size() / 3));
  HandleTargets result;
  result.source = QStringLiteral("frame \"%1\" (index %2) of %3")
                      .arg(frame.name)
                      .arg(frame.index)
                      .arg(QFileInfo(path).fileName());
  result.vertex_regions = frame.vertex_regions;
  result.file_options = frame.options;
  const std::vector<int> selected = selectedVertices(rest);
  if (selected.empty()) {
    result.handles = frame.handles;
    result.targets = frame.targets;
    return result;
  }
  for (int v : selected) {
    auto it = std::find(frame.handles.begin(), frame.handles.end(), v);
    if (it == frame.handles.end())
      throw MLException(
          QStringLiteral("vertex %1 is selected on the rest layer %2 but is no handle in %3: select only "
                         "handle vertices of the file, or none to use all of them")
              .arg(v)
              .arg(describeLayer(rest))
              .arg(path));
    const size_t h = static_cast<size_t>(it - frame.handles.begin());
    result.handles.push_back(v);
    result.targets.insert(result.targets.end(), frame.targets.begin() + 3 * h,
                          frame.targets.begin() + 3 * h + 3);
  }
  result.source +=
      QStringLiteral(", the %1 selected of its %2 handles").arg(selected.size()).arg(frame.handles.size());
  return result;
}

// The same handles in ascending vertex order, the targets permuted along.
void sortByVertex(HandleTargets& handle_targets) {
  std::vector<size_t> order(handle_targets.handles.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return handle_targets.handles[a] < handle_targets.handles[b]; });
  HandleTargets sorted{{}, {}, handle_targets.source, handle_targets.vertex_regions, handle_targets.file_options};
  for (size_t i : order) {
    sorted.handles.push_back(handle_targets.handles[i]);
    sorted.targets.insert(sorted.targets.end(), handle_targets.targets.begin() + 3 * i,
                          handle_targets.targets.begin() + 3 * i + 3);
  }
  handle_targets = std::move(sorted);
}

}  // namespace

HandleTargets handleTargets(const RichParameterList& parameters, const MeshModel& rest,
                            const std::vector<double>& rest_positions, const MeshModel* target) {
  HandleTargets result;
  switch (static_cast<TargetSource>(parameters.getEnum("targetsource"))) {
    case TargetSource::kTargetLayer: {
      result.handles = selectedHandles(rest);
      const std::vector<double> target_positions = vertexPositions(*target);
      for (int v : result.handles)
        result.targets.insert(result.targets.end(), target_positions.begin() + 3 * v,
                              target_positions.begin() + 3 * v + 3);
      result.source = "target layer " + describeLayer(*target);
      break;
    }
    case TargetSource::kHandleTransform:
      result.handles = selectedHandles(rest);
      result.targets =
          transformedTargets(parameters.getMatrix44("handletransform"), result.handles, rest_positions);
      result.source = QStringLiteral("the handle transform");
      break;
    case TargetSource::kConstraintFile:
      result = constraintFileTargets(parameters, rest, rest_positions);
      break;
    default: throw MLException("targetsource: unknown value");
  }
  sortByVertex(result);
  return result;
}

}  // namespace meshik::plugin
