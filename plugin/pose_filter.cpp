#include "pose_filter.h"

#include "handle_targets.h"
#include "pose_options.h"
#include "progress.h"
#include "meshik/thread_limit.h"

#include <common/mlexception.h>
#include <common/parameters/rich_parameters.h>
// Q_DECLARE_METATYPE(Eigen::VectorXd), the type pymeshlab converts the weights from:
#include <common/plugins/interfaces/filter_plugin.h>

#include <Eigen/Core>
#include <QElapsedTimer>

namespace meshik::plugin {

RichParameterList poseParameters(const MeshDocument& document) {
  RichParameterList parameters;
  addExampleParameters(parameters, true);
  addHandleTargetParameters(parameters, document);
  addSolverOptionParameters(parameters);
  parameters.addParam(RichBool(
      "inplace", false, "Pose in place",
      "Write the pose into the current (rest) layer instead of a new layer \"MeshIK pose of ...\". The new "
      "layer keeps the rest layer's selection and does not become the current layer, so the filter can "
      "run again on the same rest layer and handles (reusing its factorization)."));
  parameters.addParam(RichInt(
      "threads", 0, "Threads",
      "Threads of the precompute and of the solve: 0 = all cores, 1 = serial. The pose is the same for any "
      "count. When several filters run at once (e.g. pymeshlab called from several Python threads), give "
      "each the cores divided by their number."));
  return parameters;
}

std::map<std::string, QVariant> applyPose(const RichParameterList& parameters, MeshDocument& document,
                                          vcg::CallBackPos* callback, SolverCache& cache, const Logger& log) {
  if (document.mm() == nullptr)
    throw MLException("no current layer: load the rest mesh and make it the current layer");
  MeshModel* target = targetLayer(parameters, document, *document.mm());
  ExampleLayers layers = readExampleLayers(document, parameters, target);
  const HandleTargets handle_targets = handleTargets(parameters, *layers.rest, layers.arrays.rest, target);
  if (callback) callback(2, "MeshIK: layers read");

  ChosenSolverOptions chosen = chooseSolverOptions(parameters, handle_targets.file_options);
  SolverOptions& options = chosen.options;
  options.threads = parameters.getInt("threads");
  options.vertex_regions = handle_targets.vertex_regions;
  if (options.threads < 0 || options.threads > kMaxThreads)
    throw MLException(QString("threads: expected 0 (all cores) or a count from 1 to %1, got %2")
                          .arg(kMaxThreads)
                          .arg(options.threads));

  QElapsedTimer clock;
  clock.start();
  const auto example_set = exampleSetOf(cache, layers, progressRange(callback, 2, 30), options.threads);
  const qint64 precompute_ms = clock.restart();
  bool reused = false;
  const auto solver =
      cache.solver(example_set, handle_targets.handles, options, progressRange(callback, 30, 60), &reused);
  const qint64 factor_ms = clock.restart();
  const SolveResult result =
      solver->solve(handle_targets.targets.data(), nullptr, progressRange(callback, 60, 99));
  const qint64 solve_ms = clock.restart();

  MeshModel& output =
      writeOutputLayer(document, *layers.rest, "pose", parameters.getBool("inplace"), result.vertices);
  log(QStringLiteral("MeshIK pose: %1 handles from %2, %3 example layers")
          .arg(handle_targets.handles.size())
          .arg(handle_targets.source)
          .arg(layers.examples.size()));
  log(QStringLiteral("MeshIK pose: options %1").arg(chosen.description));
  if (!options.vertex_regions.empty())
    log(QStringLiteral("MeshIK pose: %1 regions from the constraint file's vertex groups").arg(solver->num_regions()));
  log(QStringLiteral("MeshIK pose: weights %1, %2 iterations%3, residual %4")
          .arg(formatWeights(result.weights))
          .arg(result.iterations)
          .arg(result.converged ? " (converged)" : "")
          .arg(result.residual, 0, 'g', 6));
  if (!result.inverted_triangles.empty())
    log(QStringLiteral("MeshIK pose: %1 faces turned over against their blended deformation (the first: "
                       "face %2); the handles ask for more than the examples can follow there")
            .arg(result.inverted_triangles.size())
            .arg(result.inverted_triangles.front()));
  log(QStringLiteral("MeshIK pose: written to %1; precompute %2 ms, factorization %3 (%4 ms), solve %5 ms")
          .arg(output.label())
          .arg(precompute_ms)
          .arg(reused ? "reused" : "new")
          .arg(factor_ms)
          .arg(solve_ms));

  Eigen::VectorXd weights = Eigen::Map<const Eigen::VectorXd>(result.weights.data(), result.weights.size());
  return {{"weights", QVariant::fromValue(weights)},  {"iterations", QVariant(result.iterations)},
          {"residual", QVariant(result.residual)},    {"converged", QVariant(result.converged)},
          {"factorization_reused", QVariant(reused)}, {"layer_id", QVariant(output.id())},
          {"inverted_triangles", QVariant(static_cast<int>(result.inverted_triangles.size()))}};
}

}  // namespace meshik::plugin
