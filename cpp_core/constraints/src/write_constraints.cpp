// write_constraint_file and write_constraint_frames: constraint files from handle groups and
// their targets, checked by the reader before they replace the file.
#include "meshik/constraints/constraint_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>

namespace meshik::constraints {
namespace {

using OrderedJson = nlohmann::ordered_json;

// `count` points (#count by 3 row-major) as a JSON list of [x, y, z]; ConstraintError naming
// `where` and the vertex (from `vertices`, when given) for a coordinate that is not finite.
OrderedJson point_list(const std::string& where, const double* points, std::size_t count,
                       const std::vector<std::int64_t>* vertices) {
  OrderedJson list = OrderedJson::array();
  for (std::size_t v = 0; v < count; ++v) {
    const double* p = points + 3 * v;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw ConstraintError(where + (vertices ? "the target of vertex " + std::to_string((*vertices)[v])
                                              : "coordinate " + std::to_string(v)) +
                            " is not finite");
    list.push_back({p[0], p[1], p[2]});
  }
  return list;
}

// The axis (unit) and angle in [0, pi] of a rotation matrix (row-major 3 by 3): the angle from
// atan2 of its skew and symmetric parts (accurate near 0 and near pi), the axis from the skew part,
// or past a right angle from the symmetric part's largest column, signed by the skew part.
// Plain arithmetic, no aligned temporaries (sanitized builds run it on a fake stack).
double axis_angle(const std::array<double, 9>& r, Vec3& axis) {
  const Vec3 skew{r[7] - r[5], r[2] - r[6], r[3] - r[1]};  // 2 sin(angle) axis
  const double twice_sin = std::sqrt(skew[0] * skew[0] + skew[1] * skew[1] + skew[2] * skew[2]);
  const double twice_cos = r[0] + r[4] + r[8] - 1.0;
  const double angle = std::atan2(twice_sin, twice_cos);
  if (angle == 0.0) return 0.0;
  if (twice_cos >= 0.0) {
    for (int k = 0; k < 3; ++k) axis[k] = skew[k] / twice_sin;
    return angle;
  }
  // (R + R^T) / 2 = cos I + (1 - cos) a a^T: the column of a a^T with the largest diagonal.
  const double c = twice_cos / 2.0;
  int j = 0;
  for (int k = 1; k < 3; ++k)
    if (r[4 * k] > r[4 * j]) j = k;
  double norm = 0.0;
  for (int k = 0; k < 3; ++k) {
    axis[k] = (r[3 * k + j] + r[3 * j + k]) / 2.0 - (k == j ? c : 0.0);
    norm += axis[k] * axis[k];
  }
  norm = std::sqrt(norm);
  const double sign = axis[0] * skew[0] + axis[1] * skew[1] + axis[2] * skew[2] < 0.0 ? -1.0 : 1.0;
  for (int k = 0; k < 3; ++k) axis[k] *= sign / norm;
  return angle;
}

// A rigid target as {"rotate": {"axis", "degrees", "center"}, "translate"}.
OrderedJson rigid_target(const std::string& where, const GroupTarget& target) {
  Vec3 axis{0.0, 0.0, 0.0};
  const double angle = axis_angle(target.rotation, axis);
  OrderedJson json = OrderedJson::object();
  if (angle != 0.0) {
    OrderedJson rotate = {{"axis", point_list(where + "rotate.axis: ", axis.data(), 1, nullptr)[0]},
                          {"degrees", angle * 180.0 / M_PI}};
    if (target.center) rotate["center"] = point_list(where + "rotate.center: ", target.center->data(), 1, nullptr)[0];
    json["rotate"] = std::move(rotate);
  }
  json["translate"] = point_list(where + "translate: ", target.translation.data(), 1, nullptr)[0];
  return json;
}

// The document's JSON text; ConstraintError for shapes that do not match or numbers that are not
// finite (what the format's checks cannot see once the numbers are written).
std::string document_text(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                          const std::vector<HandleGroup>& groups, const std::vector<Frame>& frames,
                          const WrittenSettings& settings) {
  OrderedJson document = {{"format", "meshik-constraints"}, {"version", 1}, {"rest", rest}, {"examples", examples}};
  if (settings.feature_space) document["feature_space"] = *settings.feature_space;
  if (settings.blend) document["blend"] = *settings.blend;
  if (settings.regions) {
    if (*settings.regions == -1)
      document["regions"] = "auto";
    else
      document["regions"] = *settings.regions;
  }
  if (settings.region_smoothness) document["region_smoothness"] = *settings.region_smoothness;
  for (const auto& [name, value] : {std::pair{"weight_regularization", settings.weight_regularization},
                                     std::pair{"handle_stiffness", settings.handle_stiffness}}) {
    if (!value) continue;
    if (!std::isfinite(*value)) throw ConstraintError(path + ": " + name + ": expected a finite number >= 0");
    document[name] = *value;
  }
  if (settings.max_iterations) document["max_iterations"] = *settings.max_iterations;
  OrderedJson handles = OrderedJson::object();
  for (const HandleGroup& group : groups) {
    const std::string where = path + ": handle group \"" + group.name + "\": ";
    if (group.name.rfind('_', 0) == 0)
      throw ConstraintError(where + "names starting with \"_\" are notes, not handle groups");
    if (handles.contains(group.name)) throw ConstraintError(where + "the name is given twice");
    handles[group.name] = group.vertices;
  }
  OrderedJson written_frames = OrderedJson::array();
  for (const Frame& frame : frames) {
    OrderedJson targets = OrderedJson::object();
    for (const GroupTarget& target : frame.targets) {
      const std::string where = path + ": " + (frames.size() > 1 ? "frame \"" + frame.name + "\": " : std::string()) +
                                "handle group \"" + target.group + "\": ";
      const auto group = std::find_if(groups.begin(), groups.end(),
                                      [&](const HandleGroup& g) { return g.name == target.group; });
      if (group == groups.end()) throw ConstraintError(where + "no such handle group");
      if (target.rigid) {
        targets[target.group] = rigid_target(where, target);
        continue;
      }
      if (target.positions.size() != 3 * group->vertices.size())
        throw ConstraintError(where + std::to_string(group->vertices.size()) + " vertices but " +
                              std::to_string(target.positions.size()) +
                              " target coordinates (expected 3 per vertex)");
      targets[target.group] = point_list(where, target.positions.data(), group->vertices.size(), &group->vertices);
    }
    written_frames.push_back({{"name", frame.name}, {"targets", std::move(targets)}});
  }
  document["handles"] = std::move(handles);
  document["frames"] = std::move(written_frames);
  return document.dump(1) + "\n";
}

// Checks `text` with the reader, then writes it to a temporary file beside `path` and renames it over `path`.
void replace_file(const std::string& path, const std::string& text) {
  parse_constraints(text, path);  // the written file must read back: names, vertices, frame names
  const std::string temporary = path + ".tmp-meshik";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      const int error = errno;
      std::remove(temporary.c_str());
      throw ConstraintError(path + ": cannot write the constraint file: " + std::strerror(error));
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw ConstraintError(path + ": cannot write the constraint file: " + error.message());
  }
}

}  // namespace

void write_constraint_frames(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                             const std::vector<HandleGroup>& groups, const std::vector<Frame>& frames,
                             const WrittenSettings& settings) {
  std::string text;
  try {
    text = document_text(path, rest, examples, groups, frames, settings);
  } catch (const nlohmann::json::exception& error) {  // a name that is not UTF-8
    throw ConstraintError(path + ": cannot write the constraint file: " + error.what());
  }
  replace_file(path, text);
}

void write_constraint_file(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                           const std::vector<GroupPositions>& groups, const std::string& frame_name,
                           const WrittenSettings& settings) {
  std::vector<HandleGroup> handle_groups;
  Frame frame{frame_name, {}};
  for (const GroupPositions& group : groups) {
    if (group.targets.size() != 3 * group.vertices.size())
      throw ConstraintError(path + ": handle group \"" + group.name + "\": " + std::to_string(group.vertices.size()) +
                            " vertices but " + std::to_string(group.targets.size()) +
                            " target coordinates (expected 3 per vertex)");
    handle_groups.push_back({group.name, group.vertices, std::nullopt, 0.0});
    GroupTarget target;
    target.group = group.name;
    target.positions = group.targets;
    frame.targets.push_back(std::move(target));
  }
  write_constraint_frames(path, rest, examples, handle_groups, {frame}, settings);
}

}  // namespace meshik::constraints
