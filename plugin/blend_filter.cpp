#include "blend_filter.h"

#include "layer_arrays.h"
#include "progress.h"

#include <common/mlexception.h>
#include <common/parameters/rich_parameters.h>

#include <QRegularExpression>
#include <QStringList>

#include <cmath>

namespace meshik::plugin {
namespace {

// "1, 0, 0": 1 for the first default example layer of the current layer, 0 for the others.
QString defaultWeights(const MeshDocument& document) {
  const MeshModel* rest = document.mm();
  QStringList weights;
  if (rest != nullptr)
    for (const MeshModel& layer : document.meshIterator())
      if (isDefaultExample(layer, *rest, nullptr)) weights << (weights.isEmpty() ? "1" : "0");
  return weights.isEmpty() ? QStringLiteral("1") : weights.join(", ");
}

// #E weights parsed from the "weights" parameter (numbers separated by commas or spaces).
std::vector<double> parseWeights(const QString& text, size_t num_examples) {
  std::vector<double> weights;
  for (const QString& item : text.split(QRegularExpression("[,\\s]+"), Qt::SkipEmptyParts)) {
    bool ok = false;
    const double w = item.toDouble(&ok);
    if (!ok || !std::isfinite(w)) throw MLException("weights: \"" + item + "\" is not a number");
    weights.push_back(w);
  }
  if (weights.size() != num_examples)
    throw MLException(QStringLiteral("weights: expected %1 numbers (one per example layer), got %2")
                          .arg(num_examples)
                          .arg(weights.size()));
  return weights;
}

}  // namespace

RichParameterList blendParameters(const MeshDocument& document) {
  RichParameterList parameters;
  addExampleParameters(parameters, false);
  parameters.addParam(RichString(
      "weights", defaultWeights(document), "Weights",
      "One weight per example layer, in the order of the example layers (layer order, or the order of "
      "\"Example layers\"), separated by commas. 0 for every example gives the rest pose, 1 for one "
      "example and 0 for the others gives that example; other values blend or extrapolate."));
  return parameters;
}

std::map<std::string, QVariant> applyBlend(const RichParameterList& parameters, MeshDocument& document,
                                           vcg::CallBackPos* callback, SolverCache& cache,
                                           const Logger& log) {
  ExampleLayers layers = readExampleLayers(document, parameters, nullptr);
  const std::vector<double> weights = parseWeights(parameters.getString("weights"), layers.examples.size());
  const auto example_set = exampleSetOf(cache, layers, progressRange(callback, 0, 90));
  const std::vector<double> positions = example_set->blend(weights.data(), featureSpace(parameters));
  MeshModel& output = writeOutputLayer(document, *layers.rest, "blend", false, positions);
  log(QStringLiteral("MeshIK blend: weights %1 of %2 example layers written to %3")
          .arg(formatWeights(weights))
          .arg(layers.examples.size())
          .arg(output.label()));
  return {{"layer_id", QVariant(output.id())}};
}

}  // namespace meshik::plugin
