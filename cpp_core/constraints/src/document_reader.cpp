#include "document_reader.h"

#include "rigid_motion.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

namespace meshik::constraints {
namespace {

const char* const kFormatName = "meshik-constraints";
constexpr std::int64_t kFormatVersion = 1;

// The handle groups read so far: the good ones, and the names of those whose definition was bad
// (frames may name them without a second message).
struct KnownGroups {
  std::vector<HandleGroup> good;
  std::set<std::string> bad;
  std::vector<std::string> names;  // every group's name, good or bad, in the file's order
  std::unordered_map<std::string, std::size_t> index;  // name -> position in `good` (constant-time lookups)
  bool member_ok = true;  // "handles" was an object with at least one group

  const HandleGroup* find(const std::string& name) const {
    const auto found = index.find(name);
    return found == index.end() ? nullptr : &good[found->second];
  }
};

// The frame rates accepted: key times k / fps must stay finite and distinct in the float32 seconds
// of a glTF animation for any frame count the format allows.
constexpr double kMinFps = 1e-3, kMaxFps = 1e4;

// Whether `name` can be a file name: a letter, digit, '_' or '-', then up to 99 of those or '.'.
bool is_frame_name(const std::string& name) {
  if (name.empty() || name.size() > 100 || name[0] == '.') return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

void read_format(const JsonValue& top, ViolationList& problems) {
  if (const JsonValue* format = top.find("format"))
    if (format->kind != JsonValue::Kind::String || format->text != kFormatName)
      problems.add("format", std::string("expected \"") + kFormatName + "\", got " + describe(*format));
  if (const JsonValue* value = top.find("version")) {
    const auto version = expect_int(*value, "version", problems, 1, "an integer version");
    if (version && *version != kFormatVersion)
      problems.add("version", "version " + std::to_string(*version) + " is not supported (this MeshIK reads version " +
                                  std::to_string(kFormatVersion) + ")");
  }
  if (const JsonValue* schema = top.find("$schema")) expect_string(*schema, "$schema", problems);
}

void read_mesh_names(const JsonValue& top, ConstraintDocument& document, ViolationList& problems) {
  if (const JsonValue* rest = top.find("rest"))
    if (auto name = expect_string(*rest, "rest", problems)) document.rest = *name;
  const JsonValue* examples = top.find("examples");
  if (!examples) return;
  if (examples->kind == JsonValue::Kind::String) {
    if (auto pattern = expect_string(*examples, "examples", problems)) document.examples_glob = *pattern;
    return;
  }
  if (!expect_list(*examples, "examples", problems, true)) return;
  for (std::size_t i = 0; i < examples->elements.size(); ++i)
    if (auto name = expect_string(examples->elements[i], child_path("examples", i), problems))
      document.examples.push_back(*name);
}

// "regions": a count >= 1, "auto", or an object of named vertex-index lists (no vertex twice).
std::optional<RegionSetting> read_regions(const JsonValue& value, ViolationList& problems) {
  RegionSetting setting;
  if (value.kind == JsonValue::Kind::String) {
    if (value.text != "auto") {
      problems.add("regions", "expected a count, \"auto\" or vertex groups, got \"" + value.text + "\"");
      return std::nullopt;
    }
    setting.automatic = true;
    return setting;
  }
  if (value.kind == JsonValue::Kind::Number) {
    const auto count = expect_int(value, "regions", problems, 1, "a region count");
    if (!count) return std::nullopt;
    setting.count = *count;
    return setting;
  }
  if (!expect_object(value, "regions", problems)) return std::nullopt;
  std::map<std::int64_t, std::string> owner;
  for (const auto& [name, vertices] : value.members) {
    if (name.rfind('_', 0) == 0) continue;  // a note
    const std::string path = "regions." + name;
    if (!expect_list(vertices, path, problems, true)) return std::nullopt;
    RegionGroup group{name, {}};
    for (std::size_t i = 0; i < vertices.elements.size(); ++i) {
      const auto vertex = expect_int(vertices.elements[i], child_path(path, i), problems, 0, "a vertex index");
      if (!vertex) return std::nullopt;
      if (!owner.emplace(*vertex, name).second) {
        problems.add(child_path(path, i), "vertex " + std::to_string(*vertex) + " is already in region \"" +
                                              owner[*vertex] + "\"");
        return std::nullopt;
      }
      group.vertices.push_back(*vertex);
    }
    setting.groups.push_back(std::move(group));
  }
  if (setting.groups.empty()) {
    problems.add("regions", "expected at least one vertex group");
    return std::nullopt;
  }
  return setting;
}

// The top-level member `name`, when present, as one of two strings (first or second).
std::optional<std::string> read_choice(const JsonValue& top, const std::string& name, const std::string& first,
                                       const std::string& second, ViolationList& problems) {
  const JsonValue* value = top.find(name);
  if (value == nullptr) return std::nullopt;
  const auto text = expect_string(*value, name, problems);
  if (!text || *text == first || *text == second) return text;
  problems.add(name, "expected \"" + first + "\" or \"" + second + "\", got \"" + *text + "\"");
  return std::nullopt;
}

void read_options(const JsonValue& top, ConstraintDocument& document, ViolationList& problems) {
  document.blend = read_choice(top, "blend", "affine", "free", problems);
  if (const JsonValue* value = top.find("regions")) document.regions = read_regions(*value, problems);
  if (const JsonValue* value = top.find("region_smoothness"))
    document.region_smoothness = expect_number(*value, "region_smoothness", problems, 0.0);
  document.feature_space = read_choice(top, "feature_space", "nonlinear", "linear", problems);
  if (const JsonValue* value = top.find("weight_regularization"))
    document.weight_regularization = expect_number(*value, "weight_regularization", problems, 0.0);
  if (const JsonValue* value = top.find("handle_stiffness"))
    document.handle_stiffness = expect_number(*value, "handle_stiffness", problems, 0.0);
  if (const JsonValue* value = top.find("max_iterations")) {
    document.max_iterations = expect_int(*value, "max_iterations", problems, 1);
    constexpr std::int64_t kMaxIterations = std::numeric_limits<std::int32_t>::max();
    if (document.max_iterations && *document.max_iterations > kMaxIterations) {
      problems.add("max_iterations", "expected at most " + std::to_string(kMaxIterations) + ", got " +
                                         std::to_string(*document.max_iterations));
      document.max_iterations.reset();
    }
  }
  if (const JsonValue* value = top.find("tolerance"))
    document.tolerance = expect_number(*value, "tolerance", problems, 0.0, true);
  if (const JsonValue* value = top.find("fps"))
    if (auto fps = expect_number(*value, "fps", problems, 0.0, true)) {
      if (*fps < kMinFps || *fps > kMaxFps)
        problems.add("fps", "expected a frame rate from " + format_general(kMinFps) + " to " + format_general(kMaxFps) +
                                ", got " + value->text);
      else
        document.fps = *fps;
    }
}

// One handle group (a vertex-index list or a {near, radius} region); `owner` maps each vertex
// index named so far to its group. Returns nullopt (and records why) when it is bad.
std::optional<HandleGroup> read_group(const std::string& name, const JsonValue& spec, const std::string& path,
                                      std::map<std::int64_t, std::string>& owner, ViolationList& problems) {
  if (is_blank(name)) {
    problems.add(path, "handle group names must not be empty");
    return std::nullopt;
  }
  HandleGroup group;
  group.name = name;
  if (spec.kind == JsonValue::Kind::Object) {
    const std::size_t before = problems.size();
    check_members(spec, path, {"near", "radius"}, {}, problems);
    if (const JsonValue* near = spec.find("near")) group.near = expect_numbers<3>(*near, child_path(path, "near"), problems);
    if (const JsonValue* radius = spec.find("radius"))
      group.radius = expect_number(*radius, child_path(path, "radius"), problems, 0.0, true).value_or(0.0);
    if (problems.size() != before) return std::nullopt;
    return group;
  }
  if (spec.kind != JsonValue::Kind::List) {
    problems.add(path, "expected a list of vertex indices or a region {\"near\", \"radius\"}, got " + describe(spec));
    return std::nullopt;
  }
  if (!expect_list(spec, path, problems, true)) return std::nullopt;
  const std::size_t before = problems.size();
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const std::string index_path = child_path(path, i);
    const auto index = expect_int(spec.elements[i], index_path, problems, 0, "a vertex index");
    if (!index) continue;
    const auto taken = owner.find(*index);
    if (taken != owner.end()) {
      problems.add(index_path, "vertex " + std::to_string(*index) + " is already a handle " +
                                   (taken->second == name ? std::string("earlier in this group")
                                                          : "in handle group \"" + taken->second + "\""));
      continue;
    }
    owner[*index] = name;
    group.vertices.push_back(*index);
  }
  if (problems.size() != before) return std::nullopt;
  return group;
}

KnownGroups read_handles(const JsonValue& value, ViolationList& problems) {
  KnownGroups groups;
  if (!expect_object(value, "handles", problems)) {
    groups.member_ok = false;
    return groups;
  }
  std::map<std::int64_t, std::string> owner;
  for (const auto& [name, spec] : value.members) {
    if (name.rfind('_', 0) == 0) continue;  // the user's own annotation
    groups.names.push_back(name);
    auto group = read_group(name, spec, child_path("handles", name), owner, problems);
    if (group) {
      groups.index.emplace(group->name, groups.good.size());
      groups.good.push_back(std::move(*group));
    }
    else
      groups.bad.insert(name);
  }
  if (groups.names.empty()) {
    problems.add("handles", "expected at least one handle group");
    groups.member_ok = false;  // frames naming groups say nothing more
  }
  return groups;
}

// A 4 by 4 row-major rigid transform [[R t], [0 0 0 1]] as a motion about the origin.
bool read_matrix(const JsonValue& value, const std::string& path, GroupTarget& target, ViolationList& problems) {
  if (value.kind != JsonValue::Kind::List || value.elements.size() != 4) {
    problems.add(path, "expected 4 rows of 4 numbers, got " + describe(value));
    return false;
  }
  std::array<std::array<double, 4>, 4> m{};
  bool complete = true;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto row = expect_numbers<4>(value.elements[i], child_path(path, i), problems);
    if (row) m[i] = *row;
    complete = complete && row.has_value();
  }
  if (!complete) return false;
  for (int j = 0; j < 4; ++j)
    if (!(std::fabs(m[3][j] - (j == 3 ? 1.0 : 0.0)) <= 1e-9)) {
      problems.add(child_path(path, 3), "expected the last row [0, 0, 0, 1]");
      return false;
    }
  target.rotation = {m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]};
  if (!is_rotation(target.rotation)) {
    problems.add(path, "not a rigid motion: the upper-left 3 by 3 block is not a rotation");
    return false;
  }
  target.translation = {m[0][3], m[1][3], m[2][3]};
  target.center = Vec3{0, 0, 0};
  return true;
}

// {"axis", "degrees"[, "center"]}: sets the target's rotation (and center).
bool read_rotate(const JsonValue& value, const std::string& path, GroupTarget& target, ViolationList& problems) {
  if (!expect_object(value, path, problems)) return false;
  const std::size_t before = problems.size();
  check_members(value, path, {"axis", "degrees"}, {"center"}, problems);
  std::optional<Vec3> axis;
  if (const JsonValue* axis_value = value.find("axis")) {
    axis = expect_numbers<3>(*axis_value, child_path(path, "axis"), problems);
    const double length = axis ? std::sqrt((*axis)[0] * (*axis)[0] + (*axis)[1] * (*axis)[1] + (*axis)[2] * (*axis)[2]) : 1.0;
    if (!std::isfinite(length) || length < 1e-12) {
      problems.add(child_path(path, "axis"), "the rotation axis must have a non-zero, finite length");
      axis.reset();
    }
  }
  std::optional<double> degrees;
  if (const JsonValue* degrees_value = value.find("degrees"))
    degrees = expect_number(*degrees_value, child_path(path, "degrees"), problems);
  if (const JsonValue* center = value.find("center"))
    target.center = expect_numbers<3>(*center, child_path(path, "center"), problems);
  if (problems.size() != before) return false;
  target.rotation = axis_angle_matrix(*axis, *degrees);
  return true;
}

// A rigid motion: "matrix" (4 by 4, rows), or "rotate" and/or "translate" (rotation applied first).
bool read_rigid(const JsonValue& spec, const std::string& path, GroupTarget& target, ViolationList& problems) {
  target.rigid = true;
  if (!check_members(spec, path, {}, {"translate", "rotate", "matrix"}, problems)) return false;
  const JsonValue* matrix = spec.find("matrix");
  const JsonValue* translate = spec.find("translate");
  const JsonValue* rotate = spec.find("rotate");
  if (matrix) {
    if (translate || rotate) {
      problems.add(path, "\"matrix\" cannot be combined with \"translate\" or \"rotate\"");
      return false;
    }
    return read_matrix(*matrix, child_path(path, "matrix"), target, problems);
  }
  if (!translate && !rotate) {
    problems.add(path, "expected \"translate\", \"rotate\" or \"matrix\"");
    return false;
  }
  bool ok = true;
  if (translate) {
    const auto translation = expect_numbers<3>(*translate, child_path(path, "translate"), problems);
    if (translation) target.translation = *translation;
    ok = translation.has_value();
  }
  if (rotate) ok = read_rotate(*rotate, child_path(path, "rotate"), target, problems) && ok;
  return ok;
}

// A group's target in one frame: a list of [x, y, z] positions or a rigid motion object.
std::optional<GroupTarget> read_target(const JsonValue& spec, const HandleGroup& group, const std::string& path,
                                       ViolationList& problems) {
  GroupTarget target;
  target.group = group.name;
  target.path = path;
  if (spec.kind == JsonValue::Kind::Object) {
    if (!read_rigid(spec, path, target, problems)) return std::nullopt;
    return target;
  }
  if (spec.kind != JsonValue::Kind::List) {
    problems.add(path, "expected a list of [x, y, z] positions or a rigid motion object, got " + describe(spec));
    return std::nullopt;
  }
  if (!group.near && spec.elements.size() != group.vertices.size()) {
    problems.add(path, "expected " + std::to_string(group.vertices.size()) + " positions (one per handle vertex), got " +
                           std::to_string(spec.elements.size()));
    return std::nullopt;
  }
  if (spec.elements.empty()) {
    problems.add(path, "expected at least one position");
    return std::nullopt;
  }
  bool complete = true;
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const auto position = expect_numbers<3>(spec.elements[i], child_path(path, i), problems);
    if (position) target.positions.insert(target.positions.end(), position->begin(), position->end());
    complete = complete && position.has_value();
  }
  if (!complete) return std::nullopt;
  return target;
}

// "no handle group named ..." with the list of the groups.
std::string unknown_group(const std::string& name, const KnownGroups& groups) {
  std::string known;
  for (const std::string& group : groups.names) known += (known.empty() ? "\"" : ", \"") + group + "\"";
  return "no handle group named \"" + name + "\" (groups: " + known + ")";
}

void read_frame_targets(const JsonValue& targets, const std::string& path, const KnownGroups& groups, Frame& frame,
                        ViolationList& problems) {
  for (const auto& [name, spec] : targets.members) {
    if (name.rfind('_', 0) == 0) continue;  // the user's own annotation
    const std::string target_path = child_path(path, name);
    const HandleGroup* group = groups.find(name);
    if (!group) {
      if (groups.member_ok && !groups.bad.count(name)) problems.add(target_path, unknown_group(name, groups));
      continue;
    }
    if (auto target = read_target(spec, *group, target_path, problems)) frame.targets.push_back(std::move(*target));
  }
}

std::vector<Frame> read_frames(const JsonValue& value, const KnownGroups& groups, ViolationList& problems) {
  std::vector<Frame> frames;
  if (!expect_list(value, "frames", problems, true)) return frames;
  std::map<std::string, std::size_t> seen;
  for (std::size_t number = 0; number < value.elements.size(); ++number) {
    const std::string path = child_path("frames", number);
    const JsonValue& spec = value.elements[number];
    if (!expect_object(spec, path, problems)) continue;
    check_members(spec, path, {}, {"name", "targets"}, problems);
    Frame frame;
    char numbered[32];
    std::snprintf(numbered, sizeof numbered, "%04zu", number + 1);
    frame.name = numbered;
    const JsonValue* name = spec.find("name");
    if (name) {
      const std::string name_path = child_path(path, "name");
      if (auto text = expect_string(*name, name_path, problems)) {
        frame.name = *text;
        if (!is_frame_name(*text))
          problems.add(name_path, quoted_text(*text) + " cannot be a file name: use letters, digits, \".\", \"_\", \"-\" (at most 100)");
      }
    }
    // Names given and default names ("0002" for frames[1]) share one set of output files.
    const auto [earlier, fresh] = seen.emplace(frame.name, number);
    if (!fresh)
      problems.add(name ? child_path(path, "name") : path,
                   (name ? "\"" + frame.name + "\" is" : "its default name \"" + frame.name + "\" is") +
                       " also the name of frames[" + std::to_string(earlier->second) + "]");
    if (const JsonValue* targets = spec.find("targets")) {
      const std::string targets_path = child_path(path, "targets");
      if (expect_object(*targets, targets_path, problems)) read_frame_targets(*targets, targets_path, groups, frame, problems);
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace

std::string violation_message(const std::string& source, const Violation& violation) {
  return source + ": " + (violation.path.empty() ? std::string("top level") : violation.path) + ": " + violation.problem;
}

ConstraintDocument read_document(const JsonValue& top, const std::string& source, ViolationList& problems) {
  ConstraintDocument document;
  document.source = source;
  if (!expect_object(top, "", problems)) return document;
  check_members(top, "", {"format", "version", "rest", "examples", "handles", "frames"},
                {"$schema", "feature_space", "blend", "regions", "region_smoothness", "weight_regularization",
                 "handle_stiffness", "max_iterations", "tolerance", "fps"},
                problems);
  read_format(top, problems);
  read_mesh_names(top, document, problems);
  KnownGroups groups;
  if (const JsonValue* handles = top.find("handles"))
    groups = read_handles(*handles, problems);
  else
    groups.member_ok = false;
  if (const JsonValue* frames = top.find("frames")) document.frames = read_frames(*frames, groups, problems);
  read_options(top, document, problems);
  document.handles = std::move(groups.good);
  return document;
}

}  // namespace meshik::constraints
