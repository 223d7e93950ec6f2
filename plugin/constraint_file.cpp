#include "constraint_file.h"

#include "meshik/constraints/constraint_file.h"
#include "meshik/option_names.h"

#include <algorithm>
#include <climits>
#include <string>

namespace meshik::plugin {

namespace {

// #V region ids of the document's vertex-group regions (-1: in no group), or empty without them.
// Throws ConstraintError naming the file and group of a vertex out of range.
std::vector<int> vertexRegions(const meshik::constraints::ConstraintDocument& document, int num_vertices) {
  std::vector<int> regions;
  if (!document.regions || document.regions->groups.empty()) return regions;
  regions.assign(num_vertices, -1);
  const auto& groups = document.regions->groups;
  for (std::size_t number = 0; number < groups.size(); ++number)
    for (const std::int64_t v : groups[number].vertices) {
      if (v < 0 || v >= num_vertices)
        throw meshik::constraints::ConstraintError(document.source + ": regions." + groups[number].name + ": vertex " +
                                                   std::to_string(v) + " is out of range (the rest mesh has " +
                                                   std::to_string(num_vertices) + " vertices)");
      regions[v] = static_cast<int>(number);
    }
  return regions;
}

// The solver options `document` sets (the reader has checked their values).
FileSolverOptions fileSolverOptions(const meshik::constraints::ConstraintDocument& document) {
  FileSolverOptions options;
  if (document.feature_space) options.feature_space = feature_space_from_name(*document.feature_space);
  if (document.blend) options.blend = blend_from_name(*document.blend);
  if (document.regions && document.regions->groups.empty())
    options.regions = document.regions->automatic
                          ? kAutomaticRegions
                          : static_cast<int>(std::min<std::int64_t>(document.regions->count, INT_MAX));
  options.region_smoothness = document.region_smoothness;
  options.weight_regularization = document.weight_regularization;
  options.handle_stiffness = document.handle_stiffness;
  if (document.max_iterations) options.max_iterations = static_cast<int>(*document.max_iterations);
  options.tolerance = document.tolerance;
  return options;
}

}  // namespace

ConstraintFrame readConstraintFrame(const QString& path, const QString& frame, const double* rest_vertices,
                                    int num_vertices) {
  namespace mc = meshik::constraints;
  const mc::ConstraintDocument document = mc::read_constraint_file(path.toStdString());
  const std::int64_t chosen = mc::find_frame(document, frame.toStdString());
  const mc::ResolvedConstraints resolved = mc::resolve_constraints(document, rest_vertices, num_vertices, chosen);
  ConstraintFrame result;
  result.name = QString::fromStdString(resolved.frame_names.back());
  result.index = static_cast<int>(chosen);
  result.handles.assign(resolved.handles.begin(), resolved.handles.end());
  const std::size_t last_frame = 3 * resolved.handles.size() * static_cast<std::size_t>(chosen);
  result.targets.assign(resolved.targets.begin() + static_cast<std::ptrdiff_t>(last_frame), resolved.targets.end());
  result.vertex_regions = vertexRegions(document, num_vertices);
  result.options = fileSolverOptions(document);
  return result;
}

}  // namespace meshik::plugin
