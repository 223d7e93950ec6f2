#include "constraint_file.h"

#include "json_checks.h"

#include <QFile>
#include <QJsonDocument>
#include <QJsonParseError>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace meshik::plugin {
namespace {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<double, 9>;  // row-major

const QString kFormatName = QStringLiteral("meshik-constraints");
constexpr int kFormatVersion = 1;

// A handle group: vertex indices, or every rest vertex within `radius` of `near`.
struct HandleSpec {
  QString name;
  std::vector<int> vertices;  // empty for a region
  std::optional<Vec3> near;
  double radius = 0.0;
};

// A group's target in one frame: per-vertex positions, or p -> rotation (p - center) + center + translation.
struct TargetSpec {
  QString path;                   // JSON path, for messages
  std::vector<double> positions;  // #group by 3, empty for a rigid motion
  Mat3 rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 translation{0, 0, 0};
  std::optional<Vec3> center;  // none: the centroid of the group's rest positions
};

struct FrameSpec {
  QString name;
  std::map<QString, TargetSpec> targets;  // group name -> target
};

// 3 by 3 rotation by `degrees` (right-handed) about `axis` (non-zero length), Rodrigues' formula.
Mat3 axisAngleMatrix(const Vec3& axis, double degrees) {
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double x = axis[0] / length, y = axis[1] / length, z = axis[2] / length;
  const double angle = degrees * M_PI / 180.0, c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  // clang-format off
  return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y,
          t * x * y + s * z, t * y * y + c,     t * y * z - s * x,
          t * x * z - s * y, t * y * z + s * x, t * z * z + c};
  // clang-format on
}

// Whether a row-major 3 by 3 matrix is orthonormal with determinant +1, within 1e-5.
bool isRotation(const Mat3& r) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dot = r[i] * r[j] + r[3 + i] * r[3 + j] + r[6 + i] * r[6 + j];
      if (std::fabs(dot - (i == j ? 1.0 : 0.0)) > 1e-5) return false;
    }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
  return std::fabs(det - 1.0) <= 1e-5;
}

std::vector<HandleSpec> parseHandles(const QJsonValue& value) {
  const QJsonObject groups = expectObject(value, "handles");
  if (groups.isEmpty()) throw SchemaViolation("handles", "expected at least one handle group");
  std::vector<HandleSpec> handles;
  std::map<int, QString> owner;
  for (auto it = groups.begin(); it != groups.end(); ++it) {
    const QString path = childPath("handles", it.key());
    if (it.key().trimmed().isEmpty()) throw SchemaViolation(path, "handle group names must not be empty");
    HandleSpec spec{it.key(), {}, std::nullopt, 0.0};
    if (it.value().isObject()) {
      const QJsonObject region = it.value().toObject();
      checkMembers(region, path, {"near", "radius"}, {});
      spec.near = expectNumbers<3>(region["near"], childPath(path, "near"));
      spec.radius = expectNumber(region["radius"], childPath(path, "radius"), 0.0, true);
    } else if (it.value().isArray()) {
      const QJsonArray indices = expectList(it.value(), path, true);
      for (int i = 0; i < indices.size(); ++i) {
        const int index = expectInt(indices[i], childPath(path, i), 0, "a vertex index");
        if (owner.count(index))
          throw SchemaViolation(
              childPath(path, i),
              QStringLiteral("vertex %1 is already a handle %2")
                  .arg(index)
                  .arg(owner[index] == it.key() ? "earlier in this group"
                                                : "in handle group \"" + owner[index] + "\""));
        owner[index] = it.key();
        spec.vertices.push_back(index);
      }
    } else {
      throw SchemaViolation(path,
                            "expected a list of vertex indices or a region {\"near\", \"radius\"}, got " +
                                describe(it.value()));
    }
    handles.push_back(std::move(spec));
  }
  return handles;
}

// A rigid motion: "matrix" (4 by 4, rows), or "rotate" and/or "translate" (rotation applied first).
TargetSpec parseRigid(const QJsonObject& spec, const QString& path) {
  checkMembers(spec, path, {}, {"translate", "rotate", "matrix"});
  TargetSpec target;
  target.path = path;
  if (spec.contains("matrix")) {
    if (spec.contains("translate") || spec.contains("rotate"))
      throw SchemaViolation(path, "\"matrix\" cannot be combined with \"translate\" or \"rotate\"");
    const QString matrix_path = childPath(path, "matrix");
    const QJsonValue rows = spec["matrix"];
    if (!rows.isArray() || rows.toArray().size() != 4)
      throw SchemaViolation(matrix_path, "expected 4 rows of 4 numbers, got " + describe(rows));
    std::array<std::array<double, 4>, 4> m;
    for (int i = 0; i < 4; ++i) m[i] = expectNumbers<4>(rows.toArray()[i], childPath(matrix_path, i));
    for (int j = 0; j < 4; ++j)
      if (std::fabs(m[3][j] - (j == 3 ? 1.0 : 0.0)) > 1e-9)
        throw SchemaViolation(childPath(matrix_path, 3), "expected the last row [0, 0, 0, 1]");
    target.rotation = {m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]};
    if (!isRotation(target.rotation))
      throw SchemaViolation(matrix_path, "not a rigid motion: the upper-left 3 by 3 block is not a rotation");
    target.translation = {m[0][3], m[1][3], m[2][3]};
    target.center = Vec3{0, 0, 0};
    return target;
  }
  if (!spec.contains("translate") && !spec.contains("rotate"))
    throw SchemaViolation(path, "expected \"translate\", \"rotate\" or \"matrix\"");
  if (spec.contains("translate"))
    target.translation = expectNumbers<3>(spec["translate"], childPath(path, "translate"));
  if (spec.contains("rotate")) {
    const QString rotate_path = childPath(path, "rotate");
    const QJsonObject rotate = expectObject(spec["rotate"], rotate_path);
    checkMembers(rotate, rotate_path, {"axis", "degrees"}, {"center"});
    const Vec3 axis = expectNumbers<3>(rotate["axis"], childPath(rotate_path, "axis"));
    const double length = std::hypot(axis[0], axis[1], axis[2]);
    if (!std::isfinite(length) || length < 1e-12)
      throw SchemaViolation(childPath(rotate_path, "axis"),
                            "the rotation axis must have a non-zero, finite length");
    target.rotation =
        axisAngleMatrix(axis, expectNumber(rotate["degrees"], childPath(rotate_path, "degrees")));
    if (rotate.contains("center"))
      target.center = expectNumbers<3>(rotate["center"], childPath(rotate_path, "center"));
  }
  return target;
}

// A group's target in one frame: a list of [x, y, z] positions or a rigid motion object.
TargetSpec parseTarget(const QJsonValue& value, const HandleSpec& handle, const QString& path) {
  if (value.isObject()) return parseRigid(value.toObject(), path);
  if (!value.isArray())
    throw SchemaViolation(
        path, "expected a list of [x, y, z] positions or a rigid motion object, got " + describe(value));
  const QJsonArray list = value.toArray();
  if (!handle.vertices.empty() && list.size() != static_cast<int>(handle.vertices.size()))
    throw SchemaViolation(path, QStringLiteral("expected %1 positions (one per handle vertex), got %2")
                                    .arg(handle.vertices.size())
                                    .arg(list.size()));
  if (list.isEmpty()) throw SchemaViolation(path, "expected at least one position");
  TargetSpec target;
  target.path = path;
  for (int i = 0; i < list.size(); ++i) {
    const Vec3 p = expectNumbers<3>(list[i], childPath(path, i));
    target.positions.insert(target.positions.end(), p.begin(), p.end());
  }
  return target;
}

std::vector<FrameSpec> parseFrames(const QJsonValue& value, const std::vector<HandleSpec>& handles) {
  const QJsonArray frames = expectList(value, "frames", true);
  std::vector<FrameSpec> parsed;
  std::map<QString, int> seen;
  for (int number = 0; number < frames.size(); ++number) {
    const QString path = childPath("frames", number);
    const QJsonObject frame = expectObject(frames[number], path);
    checkMembers(frame, path, {}, {"name", "targets"});
    FrameSpec spec;
    spec.name = frame.contains("name") ? expectString(frame["name"], childPath(path, "name"))
                                       : QStringLiteral("%1").arg(number + 1, 4, 10, QChar('0'));
    if (seen.count(spec.name))
      throw SchemaViolation(
          childPath(path, "name"),
          QStringLiteral("\"%1\" is also the name of frames[%2]").arg(spec.name).arg(seen[spec.name]));
    seen[spec.name] = number;
    const QString targets_path = childPath(path, "targets");
    const QJsonObject targets =
        expectObject(frame.contains("targets") ? frame["targets"] : QJsonObject(), targets_path);
    for (auto it = targets.begin(); it != targets.end(); ++it) {
      const QString target_path = childPath(targets_path, it.key());
      auto handle = std::find_if(handles.begin(), handles.end(),
                                 [&](const HandleSpec& h) { return h.name == it.key(); });
      if (handle == handles.end()) {
        QStringList known;
        for (const HandleSpec& h : handles) known << "\"" + h.name + "\"";
        throw SchemaViolation(
            target_path, "no handle group named \"" + it.key() + "\" (groups: " + known.join(", ") + ")");
      }
      spec.targets[it.key()] = parseTarget(it.value(), *handle, target_path);
    }
    parsed.push_back(std::move(spec));
  }
  return parsed;
}

// Vertex indices of every group, in the order of `handles`; SchemaViolation for out-of-range,
// empty or overlapping groups.
std::vector<std::vector<int>> resolveGroups(const std::vector<HandleSpec>& handles, const double* rest,
                                            int num_vertices) {
  std::vector<std::vector<int>> groups;
  std::vector<int> owner(num_vertices, -1);
  for (const HandleSpec& spec : handles) {
    const QString path = childPath("handles", spec.name);
    std::vector<int> indices = spec.vertices;
    for (size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= num_vertices)
        throw SchemaViolation(childPath(path, static_cast<int>(i)),
                              QStringLiteral("vertex %1 is out of range (the rest mesh has %2 vertices)")
                                  .arg(indices[i])
                                  .arg(num_vertices));
    if (spec.near) {
      double nearest = std::numeric_limits<double>::infinity();
      for (int v = 0; v < num_vertices; ++v) {
        const double* p = rest + 3 * v;
        const double distance =
            std::hypot(p[0] - (*spec.near)[0], p[1] - (*spec.near)[1], p[2] - (*spec.near)[2]);
        nearest = std::min(nearest, distance);
        if (distance <= spec.radius) indices.push_back(v);
      }
      if (indices.empty())
        throw SchemaViolation(
            path, QStringLiteral("no rest vertex within radius %1 of [%2, %3, %4] (the nearest is %5 away)")
                      .arg(spec.radius)
                      .arg((*spec.near)[0])
                      .arg((*spec.near)[1])
                      .arg((*spec.near)[2])
                      .arg(nearest));
    }
    for (int v : indices) {
      if (owner[v] >= 0)
        throw SchemaViolation(
            path,
            QStringLiteral("vertex %1 is also in handle group \"%2\"").arg(v).arg(handles[owner[v]].name));
      owner[v] = static_cast<int>(groups.size());
    }
    groups.push_back(std::move(indices));
  }
  return groups;
}

// #group by 3 targets of one group in one frame, from its spec and the group's rest positions.
std::vector<double> groupTargets(const TargetSpec& spec, const std::vector<double>& rest_positions) {
  const size_t count = rest_positions.size() / 3;
  if (!spec.positions.empty()) {
    if (spec.positions.size() != rest_positions.size())
      throw SchemaViolation(spec.path, QStringLiteral("expected %1 positions (one per handle vertex), got %2")
                                           .arg(count)
                                           .arg(spec.positions.size() / 3));
    return spec.positions;
  }
  Vec3 center{0, 0, 0};
  if (spec.center) {
    center = *spec.center;
  } else {
    for (size_t v = 0; v < count; ++v)
      for (int k = 0; k < 3; ++k) center[k] += rest_positions[3 * v + k] / static_cast<double>(count);
  }
  std::vector<double> moved(rest_positions.size());
  for (size_t v = 0; v < count; ++v) {
    const double d[3] = {rest_positions[3 * v] - center[0], rest_positions[3 * v + 1] - center[1],
                         rest_positions[3 * v + 2] - center[2]};
    for (int k = 0; k < 3; ++k)
      moved[3 * v + k] = spec.rotation[3 * k] * d[0] + spec.rotation[3 * k + 1] * d[1] +
                         spec.rotation[3 * k + 2] * d[2] + center[k] + spec.translation[k];
  }
  return moved;
}

// The 0-based index of the frame named `frame`, or else numbered `frame`; SchemaViolation when
// there is none.
int findFrame(const std::vector<FrameSpec>& frames, const QString& frame) {
  for (size_t i = 0; i < frames.size(); ++i)
    if (frames[i].name == frame) return static_cast<int>(i);
  bool is_number = false;
  const int index = frame.trimmed().toInt(&is_number);
  if (is_number && index >= 0 && index < static_cast<int>(frames.size())) return index;
  throw SchemaViolation("frames", QStringLiteral("no frame named or numbered \"%1\" (the file has %2 frames, "
                                                 "numbered from 0, named %3 ... %4)")
                                      .arg(frame)
                                      .arg(frames.size())
                                      .arg(frames.front().name)
                                      .arg(frames.back().name));
}

QJsonObject parseJson(const QString& path) {
  QFile file(path);
  if (!file.exists()) throw ConstraintFileError((path + ": constraint file not found").toStdString());
  if (!file.open(QIODevice::ReadOnly))
    throw ConstraintFileError(
        (path + ": cannot read the constraint file: " + file.errorString()).toStdString());
  const QByteArray text = file.readAll();
  QJsonParseError error;
  const QJsonDocument document = QJsonDocument::fromJson(text, &error);
  if (error.error != QJsonParseError::NoError) {
    const QByteArray before = text.left(error.offset);
    const int line = before.count('\n') + 1;
    const int column = error.offset - (before.lastIndexOf('\n') + 1) + 1;
    throw ConstraintFileError(QStringLiteral("%1: not valid JSON: line %2 column %3: %4")
                                  .arg(path)
                                  .arg(line)
                                  .arg(column)
                                  .arg(error.errorString())
                                  .toStdString());
  }
  if (!document.isObject())
    throw ConstraintFileError((path + ": top level: expected an object").toStdString());
  return document.object();
}

}  // namespace

ConstraintFrame readConstraintFrame(const QString& path, const QString& frame, const double* rest_vertices,
                                    int num_vertices) {
  const QJsonObject top = parseJson(path);
  try {
    checkMembers(top, "", {"format", "version", "rest", "examples", "handles", "frames"},
                 {"feature_space", "weight_regularization", "max_iterations", "tolerance", "fps"});
    if (top["format"] != QJsonValue(kFormatName))
      throw SchemaViolation("format", "expected \"" + kFormatName + "\", got " + describe(top["format"]));
    const int version = expectInt(top["version"], "version", 1, "an integer version");
    if (version != kFormatVersion)
      throw SchemaViolation("version",
                            QStringLiteral("version %1 is not supported (this MeshIK reads version %2)")
                                .arg(version)
                                .arg(kFormatVersion));
    const std::vector<HandleSpec> handles = parseHandles(top["handles"]);
    const std::vector<FrameSpec> frames = parseFrames(top["frames"], handles);
    const int chosen = findFrame(frames, frame);
    const std::vector<std::vector<int>> groups = resolveGroups(handles, rest_vertices, num_vertices);

    // Every group starts at its rest positions and takes each frame's target up to the chosen one.
    std::vector<std::vector<double>> rest_positions(groups.size()), current(groups.size());
    for (size_t g = 0; g < groups.size(); ++g) {
      for (int v : groups[g])
        rest_positions[g].insert(rest_positions[g].end(), rest_vertices + 3 * v, rest_vertices + 3 * v + 3);
      current[g] = rest_positions[g];
    }
    for (int f = 0; f <= chosen; ++f)
      for (size_t g = 0; g < groups.size(); ++g) {
        auto target = frames[f].targets.find(handles[g].name);
        if (target != frames[f].targets.end()) current[g] = groupTargets(target->second, rest_positions[g]);
      }

    ConstraintFrame result;
    result.name = frames[chosen].name;
    result.index = chosen;
    for (size_t g = 0; g < groups.size(); ++g) {
      result.handles.insert(result.handles.end(), groups[g].begin(), groups[g].end());
      result.targets.insert(result.targets.end(), current[g].begin(), current[g].end());
    }
    return result;
  } catch (const SchemaViolation& violation) {
    const QString where = violation.path.isEmpty() ? QStringLiteral("top level") : violation.path;
    throw ConstraintFileError((path + ": " + where + ": " + violation.problem).toStdString());
  }
}

}  // namespace meshik::plugin
