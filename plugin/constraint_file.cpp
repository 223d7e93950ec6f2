#include "constraint_file.h"

#include "meshik/constraints/constraint_file.h"

namespace meshik::plugin {

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
  return result;
}

}  // namespace meshik::plugin
