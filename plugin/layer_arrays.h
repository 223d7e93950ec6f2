// MeshLab layers <-> the plain row-major double / int arrays of the MeshIK core, and the choice
// of example layers. Indices are positions in the layer's vertex / face vectors, so every layer
// used here is compacted first (MeshLab compacts after every filter, so this is rarely work).
#pragma once

#include <common/ml_document/mesh_document.h>

#include <QString>

#include <vector>

namespace meshik::plugin {

// Label of a layer for messages: `"horse.obj" (layer 3)`.
QString describeLayer(const MeshModel& layer);

// Removes deleted vertices and faces from the layer's vectors (no-op when there are none).
void compactLayer(MeshModel& layer);

// #V by 3 row-major vertex positions of a compacted layer.
std::vector<double> vertexPositions(const MeshModel& layer);

// #F by 3 row-major 0-based vertex indices of a compacted layer's triangles.
std::vector<int> triangleIndices(const MeshModel& layer);

// Ascending indices of the selected vertices of a compacted layer.
std::vector<int> selectedVertices(const MeshModel& layer);

// Overwrites the layer's vertex positions with #V by 3 row-major `positions` (#V = the layer's
// vertex count) and updates its bounding box and normals.
void setVertexPositions(MeshModel& layer, const std::vector<double>& positions);

// Overwrites the layer's vertex positions with #V by 3 row-major `positions`, its face normals
// with #F by 3 `face_normals` and its vertex normals with #V by 3 `vertex_normals` (computed
// elsewhere, say on a worker thread), and sets its bounding box. Fills `held` with the #V by 3
// positions as the layer now holds them (rounded to MeshLab's scalar), without reading the layer
// back (its storage reused: no allocation per pose).
void setVertexPositionsAndNormals(MeshModel& layer, const std::vector<double>& positions,
                                  const std::vector<double>& face_normals, const std::vector<double>& vertex_normals,
                                  std::vector<double>& held);

// Prefix of the labels of the layers the MeshIK filters create ("MeshIK pose of ...").
// Such layers are never taken as example poses by default.
extern const QString kOutputLabelPrefix;

// Whether `layer` is one of the rest layer's example layers when the user names none: another
// layer with the rest layer's vertex and triangle counts that is neither `excluded` (may be null)
// nor one of MeshIK's output layers.
bool isDefaultExample(const MeshModel& layer, const MeshModel& rest, const MeshModel* excluded);

// The example layers, compacted, for the rest layer with #F by 3 `rest_triangles`:
//   spec empty: every layer for which isDefaultExample() holds;
//   otherwise:  the layers named in `spec`, a comma-separated list of layer ids or labels.
// Throws MLException when there is none, when a named layer does not exist or is the rest layer,
// or when an example's triangles differ from the rest layer's (naming the layer and triangle).
std::vector<MeshModel*> exampleLayers(MeshDocument& document, const MeshModel& rest,
                                      const std::vector<int>& rest_triangles, const QString& spec,
                                      const MeshModel* excluded);

}  // namespace meshik::plugin
