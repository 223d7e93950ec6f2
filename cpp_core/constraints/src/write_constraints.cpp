// write_constraint_file: a one-frame constraint file from handle groups and their targets.
#include "meshik/constraints/constraint_file.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace meshik::constraints {
namespace {

using OrderedJson = nlohmann::ordered_json;

// The document's JSON text; ConstraintError for groups whose shapes do not match or targets that
// are not finite (what the format's checks cannot see once the numbers are written).
std::string document_text(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                          const std::vector<GroupPositions>& groups, const std::string& frame_name,
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
  if (settings.weight_regularization) {
    if (!std::isfinite(*settings.weight_regularization))
      throw ConstraintError(path + ": weight_regularization: expected a finite number >= 0");
    document["weight_regularization"] = *settings.weight_regularization;
  }
  if (settings.max_iterations) document["max_iterations"] = *settings.max_iterations;
  OrderedJson handles = OrderedJson::object(), targets = OrderedJson::object();
  for (const GroupPositions& group : groups) {
    const std::string where = path + ": handle group \"" + group.name + "\": ";
    if (group.targets.size() != 3 * group.vertices.size())
      throw ConstraintError(where + std::to_string(group.vertices.size()) + " vertices but " +
                            std::to_string(group.targets.size()) + " target coordinates (expected 3 per vertex)");
    OrderedJson positions = OrderedJson::array();
    for (std::size_t v = 0; v < group.vertices.size(); ++v) {
      const double* p = group.targets.data() + 3 * v;
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw ConstraintError(where + "the target of vertex " + std::to_string(group.vertices[v]) + " is not finite");
      positions.push_back({p[0], p[1], p[2]});
    }
    if (group.name.rfind('_', 0) == 0)
      throw ConstraintError(where + "names starting with \"_\" are notes, not handle groups");
    if (handles.contains(group.name)) throw ConstraintError(where + "the name is given twice");
    handles[group.name] = group.vertices;
    targets[group.name] = std::move(positions);
  }
  document["handles"] = std::move(handles);
  document["frames"] = OrderedJson::array({{{"name", frame_name}, {"targets", std::move(targets)}}});
  return document.dump(1) + "\n";
}

}  // namespace

void write_constraint_file(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                           const std::vector<GroupPositions>& groups, const std::string& frame_name,
                           const WrittenSettings& settings) {
  std::string text;
  try {
    text = document_text(path, rest, examples, groups, frame_name, settings);
  } catch (const nlohmann::json::exception& error) {  // a name that is not UTF-8
    throw ConstraintError(path + ": cannot write the constraint file: " + error.what());
  }
  parse_constraints(text, path);  // the written file must read back: names, vertices, frame name
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

}  // namespace meshik::constraints
