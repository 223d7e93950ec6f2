// What the pose and the blend filter share: the example-layer and feature-space parameters,
// reading the rest and example layers into the core's arrays, and the output layer.
#pragma once

#include "solver_cache.h"

#include <common/ml_document/mesh_document.h>
#include <common/parameters/rich_parameter_list.h>

#include <QString>

#include <functional>
#include <vector>

namespace meshik::plugin {

// Writes one line to MeshLab's log (the GUI's log window and stdout as "LOG: ...").
using Logger = std::function<void(const QString&)>;

// Adds the parameters "examplelayers" (which layers are the example poses) and "featurespace"
// (Nonlinear, Linear; with `from_constraint_file` a third entry, "From the constraint file", the
// default: pose_options.h reads it).
void addExampleParameters(RichParameterList& parameters, bool from_constraint_file);

// The feature space chosen in the "featurespace" parameter (Nonlinear or Linear).
FeatureSpace featureSpace(const RichParameterList& parameters);

// The rest layer (the document's current layer) and its example layers, read into arrays.
struct ExampleLayers {
  MeshModel* rest = nullptr;
  std::vector<MeshModel*> examples;  // #E layers
  ExampleSetInputs arrays;           // their positions and the rest layer's triangles
};

// Reads the current layer and the example layers chosen by "examplelayers" (never `excluded`,
// which may be null, unless named explicitly). Throws MLException on a missing current layer,
// no or a bad example layer.
ExampleLayers readExampleLayers(MeshDocument& document, const RichParameterList& parameters,
                                const MeshModel* excluded);

// The example set of `layers` (moving their arrays into the cache, which may reuse its previous
// one). Bad input (meshik::InputError: a non-finite coordinate, a degenerate rest triangle, ...)
// comes back as an MLException that also names the layer concerned. threads: of the precompute
// (0 = all cores).
std::shared_ptr<const ExampleSet> exampleSetOf(SolverCache& cache, ExampleLayers& layers,
                                               const ProgressCallback& progress, int threads = 0);

// The layer a filter writes its #V by 3 `positions` to: the rest layer itself when `in_place`,
// else a new copy of it (selection included) labelled "MeshIK <what> of <rest label>", which does
// not become the current layer (so the filter can run again on the same rest layer).
MeshModel& writeOutputLayer(MeshDocument& document, MeshModel& rest, const QString& what, bool in_place,
                            const std::vector<double>& positions);

// "[0.25, 0.75]": weights for log lines.
QString formatWeights(const std::vector<double>& weights);

}  // namespace meshik::plugin
