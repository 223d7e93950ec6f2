// resolve_constraints: handle groups and per-frame targets of a document against a rest mesh.
#include "meshik/constraints/constraint_file.h"

#include "json_checks.h"
#include "rigid_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace meshik::constraints {
namespace {

// Vertex indices of every group, in the document's order; ConstraintError for out-of-range,
// empty or overlapping groups.
std::vector<std::vector<std::int64_t>> resolve_groups(const ConstraintDocument& document, const double* rest,
                                                      std::int64_t num_vertices) {
  const auto fail = [&](const std::string& path, const std::string& problem) {
    return ConstraintError(document.source + ": " + path + ": " + problem);
  };
  std::vector<std::vector<std::int64_t>> groups;
  std::vector<int> owner(static_cast<std::size_t>(std::max<std::int64_t>(num_vertices, 0)), -1);
  for (const HandleGroup& group : document.handles) {
    const std::string path = child_path("handles", group.name);
    std::vector<std::int64_t> indices = group.vertices;
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= num_vertices)
        throw fail(child_path(path, i), "vertex " + std::to_string(indices[i]) + " is out of range (the rest mesh has " +
                                            std::to_string(num_vertices) + " vertices)");
    if (group.near) {
      const Vec3& near = *group.near;
      double nearest = std::numeric_limits<double>::infinity();
      for (std::int64_t v = 0; v < num_vertices; ++v) {
        const double* p = rest + 3 * v;
        const double dx = p[0] - near[0], dy = p[1] - near[1], dz = p[2] - near[2];
        const double distance = std::sqrt(dx * dx + dy * dy + dz * dz);
        nearest = std::fmin(nearest, distance);
        if (distance <= group.radius) indices.push_back(v);
      }
      if (indices.empty())
        throw fail(path, "no rest vertex within radius " + format_general(group.radius) + " of [" + format_general(near[0]) +
                             ", " + format_general(near[1]) + ", " + format_general(near[2]) + "] (the nearest is " +
                             format_general(nearest) + " away)");
    }
    for (std::int64_t v : indices) {
      if (owner[v] >= 0)
        throw fail(path, "vertex " + std::to_string(v) + " is also in handle group \"" +
                             document.handles[owner[v]].name + "\"");
      owner[v] = static_cast<int>(groups.size());
    }
    groups.push_back(std::move(indices));
  }
  return groups;
}

}  // namespace

ResolvedConstraints resolve_constraints(const ConstraintDocument& document, const double* rest_vertices,
                                        std::int64_t num_vertices, std::int64_t last_frame) {
  ResolvedConstraints resolved;
  resolved.groups = resolve_groups(document, rest_vertices, num_vertices);
  const std::size_t group_count = resolved.groups.size();
  std::vector<std::vector<double>> rest_positions(group_count), current(group_count);
  for (std::size_t g = 0; g < group_count; ++g) {
    resolved.group_names.push_back(document.handles[g].name);
    for (std::int64_t v : resolved.groups[g]) {
      rest_positions[g].insert(rest_positions[g].end(), rest_vertices + 3 * v, rest_vertices + 3 * v + 3);
      resolved.handles.push_back(v);
    }
    current[g] = rest_positions[g];
  }
  std::unordered_map<std::string, std::size_t> group_index;  // name -> g: linear in the number of groups
  for (std::size_t g = 0; g < group_count; ++g) group_index.emplace(document.handles[g].name, g);
  const std::size_t frame_count =
      last_frame < 0 ? document.frames.size() : std::min(document.frames.size(), static_cast<std::size_t>(last_frame) + 1);
  for (std::size_t f = 0; f < frame_count; ++f) {
    // Every group keeps its previous targets unless this frame names it.
    for (const GroupTarget& target : document.frames[f].targets) {
      const auto found = group_index.find(target.group);
      if (found == group_index.end()) continue;
      const std::size_t g = found->second;
      if (!target.rigid && target.positions.size() != rest_positions[g].size())
        throw ConstraintError(document.source + ": " + target.path + ": expected " +
                              std::to_string(rest_positions[g].size() / 3) + " positions (one per handle vertex), got " +
                              std::to_string(target.positions.size() / 3));
      current[g] = group_targets(target, rest_positions[g]);
    }
    for (std::size_t g = 0; g < group_count; ++g)
      resolved.targets.insert(resolved.targets.end(), current[g].begin(), current[g].end());
    resolved.frame_names.push_back(document.frames[f].name);
  }
  return resolved;
}

}  // namespace meshik::constraints
