#include "layer_arrays.h"

#include <common/mlexception.h>
#include <vcg/complex/allocate.h>

#include <algorithm>

namespace meshik::plugin {

const QString kOutputLabelPrefix = QStringLiteral("MeshIK ");

QString describeLayer(const MeshModel& layer) {
  return QStringLiteral("\"%1\" (layer %2)").arg(layer.label()).arg(layer.id());
}

void compactLayer(MeshModel& layer) {
  CMeshO& mesh = layer.cm;
  if (mesh.vn != static_cast<int>(mesh.vert.size()) || mesh.fn != static_cast<int>(mesh.face.size()))
    vcg::tri::Allocator<CMeshO>::CompactEveryVector(mesh);
}

std::vector<double> vertexPositions(const MeshModel& layer) {
  std::vector<double> positions;
  positions.reserve(3 * layer.cm.vert.size());
  for (const CVertexO& v : layer.cm.vert)
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<double>(v.cP()[k]));
  return positions;
}

std::vector<int> triangleIndices(const MeshModel& layer) {
  std::vector<int> triangles;
  triangles.reserve(3 * layer.cm.face.size());
  for (const CFaceO& f : layer.cm.face)
    for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<int>(vcg::tri::Index(layer.cm, f.cV(k))));
  return triangles;
}

std::vector<int> selectedVertices(const MeshModel& layer) {
  std::vector<int> selected;
  for (size_t i = 0; i < layer.cm.vert.size(); ++i)
    if (layer.cm.vert[i].IsS()) selected.push_back(static_cast<int>(i));
  return selected;
}

void setVertexPositions(MeshModel& layer, const std::vector<double>& positions) {
  for (size_t i = 0; i < layer.cm.vert.size(); ++i)
    layer.cm.vert[i].P() =
        Point3m(static_cast<Scalarm>(positions[3 * i]), static_cast<Scalarm>(positions[3 * i + 1]),
                static_cast<Scalarm>(positions[3 * i + 2]));
  layer.updateBoxAndNormals();
}

void setVertexPositionsAndNormals(MeshModel& layer, const std::vector<double>& positions,
                                  const std::vector<double>& face_normals, const std::vector<double>& vertex_normals,
                                  std::vector<double>& held) {
  held.resize(positions.size());
  vcg::Box3<Scalarm> box;  // grown in the same pass (UpdateBounding::Box would read every vertex again)
  for (size_t i = 0; i < layer.cm.vert.size(); ++i) {
    CVertexO& v = layer.cm.vert[i];
    for (int k = 0; k < 3; ++k) {
      v.P()[k] = static_cast<Scalarm>(positions[3 * i + k]);
      v.N()[k] = static_cast<Scalarm>(vertex_normals[3 * i + k]);
      held[3 * i + k] = static_cast<double>(v.cP()[k]);
    }
    box.Add(v.cP());
  }
  for (size_t f = 0; f < layer.cm.face.size(); ++f)
    for (int k = 0; k < 3; ++k) layer.cm.face[f].N()[k] = static_cast<Scalarm>(face_normals[3 * f + k]);
  layer.cm.bbox = box;
}

namespace {

// The layer named by one entry of the example list: a layer id, or else a layer label.
MeshModel* findLayer(MeshDocument& document, const QString& token) {
  bool is_number = false;
  const int id = token.toInt(&is_number);
  if (is_number && id >= 0 && document.getMesh(static_cast<unsigned>(id)) != nullptr)
    return document.getMesh(static_cast<unsigned>(id));
  for (MeshModel& layer : document.meshIterator())
    if (layer.label() == token) return &layer;
  throw MLException("examplelayers: no layer with id or name \"" + token + "\"");
}

// Throws when the example's vertex count or triangles differ from the rest layer's.
void checkSameTopology(const MeshModel& example, const MeshModel& rest,
                       const std::vector<int>& rest_triangles) {
  if (example.cm.vn != rest.cm.vn || example.cm.fn != rest.cm.fn)
    throw MLException(
        QStringLiteral("example layer %1 has %2 vertices and %3 triangles, the rest layer %4 has %5 and %6: "
                       "examples must have the rest mesh's vertices and triangles")
            .arg(describeLayer(example))
            .arg(example.cm.vn)
            .arg(example.cm.fn)
            .arg(describeLayer(rest))
            .arg(rest.cm.vn)
            .arg(rest.cm.fn));
  const std::vector<int> triangles = triangleIndices(example);
  for (size_t t = 0; t < triangles.size(); t += 3) {
    if (std::equal(triangles.begin() + t, triangles.begin() + t + 3, rest_triangles.begin() + t)) continue;
    throw MLException(
        QStringLiteral("example layer %1 has other triangles than the rest layer %2: triangle %3 is "
                       "(%4, %5, %6) in the example and (%7, %8, %9) in the rest mesh")
            .arg(describeLayer(example))
            .arg(describeLayer(rest))
            .arg(t / 3)
            .arg(triangles[t])
            .arg(triangles[t + 1])
            .arg(triangles[t + 2])
            .arg(rest_triangles[t])
            .arg(rest_triangles[t + 1])
            .arg(rest_triangles[t + 2]));
  }
}

}  // namespace

bool isDefaultExample(const MeshModel& layer, const MeshModel& rest, const MeshModel* excluded) {
  return layer.id() != rest.id() && &layer != excluded && !layer.label().startsWith(kOutputLabelPrefix) &&
         layer.cm.vn == rest.cm.vn && layer.cm.fn == rest.cm.fn;
}

std::vector<MeshModel*> exampleLayers(MeshDocument& document, const MeshModel& rest,
                                      const std::vector<int>& rest_triangles, const QString& spec,
                                      const MeshModel* excluded) {
  std::vector<MeshModel*> examples;
  if (spec.trimmed().isEmpty()) {
    for (MeshModel& layer : document.meshIterator()) {
      if (!isDefaultExample(layer, rest, excluded)) continue;
      compactLayer(layer);
      examples.push_back(&layer);
    }
  } else {
    for (const QString& token : spec.split(',', Qt::SkipEmptyParts)) {
      MeshModel* layer = findLayer(document, token.trimmed());
      if (layer->id() == rest.id())
        throw MLException("examplelayers: " + describeLayer(*layer) +
                          " is the rest layer (the current layer)");
      if (std::find(examples.begin(), examples.end(), layer) != examples.end())
        throw MLException("examplelayers: " + describeLayer(*layer) + " is listed twice");
      compactLayer(*layer);
      examples.push_back(layer);
    }
  }
  if (examples.empty())
    throw MLException(
        QStringLiteral("no example layer: load the example poses as layers with the rest layer %1's "
                       "%2 vertices and %3 triangles")
            .arg(describeLayer(rest))
            .arg(rest.cm.vn)
            .arg(rest.cm.fn));
  for (const MeshModel* example : examples) checkSameTopology(*example, rest, rest_triangles);
  return examples;
}

}  // namespace meshik::plugin
