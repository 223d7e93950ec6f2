// The pose filter's solver parameters and the options they give. Each parameter's default means
// "from the constraint file": the constraint file's value when the handle targets come from a file
// that sets it, else the solver's default; any other value overrides the file. So a file saved by
// the Drag to Pose tool poses as `meshik pose` poses it.
#pragma once

#include "constraint_file.h"

#include <common/parameters/rich_parameter_list.h>
#include <meshik/meshik.h>

#include <QString>

namespace meshik::plugin {

// Adds "iterations", "weightregularization", "blend", "regions", "regionsmoothness" and
// "handlestiffness" (the feature space is addExampleParameters' "featurespace").
void addSolverOptionParameters(RichParameterList& parameters);

struct ChosenSolverOptions {
  // Feature space, iterations, tolerance, weight regularization, blend, regions, region smoothness
  // and handle stiffness chosen; threads and vertex_regions left at their defaults.
  SolverOptions options;
  // "feature space nonlinear (default), blend free (constraint file), ...": each option's value and
  // where it came from (parameter, constraint file or default), for the log.
  QString description;
};

// The solver options from the parameters ("featurespace" and those above) and `file`, the
// constraint file's options (all empty when the targets come from elsewhere).
// Throws MLException naming the parameter of a bad value.
ChosenSolverOptions chooseSolverOptions(const RichParameterList& parameters, const FileSolverOptions& file);

}  // namespace meshik::plugin
