#include "filter_common.h"

#include "layer_arrays.h"

#include <common/mlexception.h>
#include <common/parameters/rich_parameters.h>

#include <QRegularExpression>
#include <QStringList>

namespace meshik::plugin {

void addExampleParameters(RichParameterList& parameters, bool from_constraint_file) {
  parameters.addParam(RichString(
      "examplelayers", "", "Example layers",
      "Which layers are the example poses. Empty: every layer other than the current (rest) layer with "
      "the rest layer's vertex and triangle counts, except the target layer and the layers MeshIK "
      "created (labels starting with \"MeshIK \"). Otherwise a comma-separated list of layer ids or "
      "layer names, e.g. \"1, 2, 5\". Every example must have the rest layer's triangles."));
  QStringList choices{"Nonlinear", "Linear"};
  QString tooltip =
      "How the examples' deformation gradients are combined. Nonlinear (the paper's): rotations and "
      "stretches are blended separately, so large rotations interpolate without shrinking. Linear: the "
      "gradients are blended linearly (faster, fine for small deformations).";
  if (from_constraint_file) {
    choices << "From the constraint file";
    tooltip += " From the constraint file (the default): the file's \"feature_space\" when the handle targets "
               "come from a constraint file that sets it, else Nonlinear.";
  }
  parameters.addParam(RichEnum("featurespace", from_constraint_file ? 2 : 0, choices, "Feature space", tooltip));
}

FeatureSpace featureSpace(const RichParameterList& parameters) {
  return parameters.getEnum("featurespace") == 1 ? FeatureSpace::kLinear : FeatureSpace::kNonlinear;
}

ExampleLayers readExampleLayers(MeshDocument& document, const RichParameterList& parameters,
                                const MeshModel* excluded) {
  ExampleLayers layers;
  layers.rest = document.mm();
  if (layers.rest == nullptr)
    throw MLException("no current layer: load the rest mesh and make it the current layer");
  compactLayer(*layers.rest);
  if (layers.rest->cm.fn == 0)
    throw MLException("the rest layer " + describeLayer(*layers.rest) + " has no triangles");
  layers.arrays.rest = vertexPositions(*layers.rest);
  layers.arrays.triangles = triangleIndices(*layers.rest);
  layers.examples = exampleLayers(document, *layers.rest, layers.arrays.triangles,
                                  parameters.getString("examplelayers"), excluded);
  for (const MeshModel* example : layers.examples)
    layers.arrays.examples.push_back(vertexPositions(*example));
  return layers;
}

std::shared_ptr<const ExampleSet> exampleSetOf(SolverCache& cache, ExampleLayers& layers,
                                               const ProgressCallback& progress, int threads) {
  try {
    return cache.exampleSet(std::move(layers.arrays), progress, threads);
  } catch (const InputError& error) {
    // The core numbers the examples from 0 in the order given: name the layer it means.
    static const QRegularExpression example_number(QStringLiteral("^example (\\d+)\\b"));
    const QString message = QString::fromUtf8(error.what());
    const QRegularExpressionMatch match = example_number.match(message);
    const size_t number = match.hasMatch() ? match.captured(1).toULong() : layers.examples.size();
    if (number < layers.examples.size())
      throw MLException(QStringLiteral("%1 (example %2 is layer %3)")
                            .arg(message, match.captured(1), describeLayer(*layers.examples[number])));
    throw MLException(
        QStringLiteral("%1 (the rest mesh is layer %2)").arg(message, describeLayer(*layers.rest)));
  }
}

MeshModel& writeOutputLayer(MeshDocument& document, MeshModel& rest, const QString& what, bool in_place,
                            const std::vector<double>& positions) {
  MeshModel* output = &rest;
  if (!in_place)
    output = document.addNewMesh(rest.cm, kOutputLabelPrefix + what + " of " + rest.label(), false);
  setVertexPositions(*output, positions);
  return *output;
}

QString formatWeights(const std::vector<double>& weights) {
  QStringList items;
  for (double w : weights) items << QString::number(w, 'g', 6);
  return "[" + items.join(", ") + "]";
}

}  // namespace meshik::plugin
