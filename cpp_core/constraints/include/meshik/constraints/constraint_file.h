// MeshIK constraint files (format "meshik-constraints", version 1; schema in
// pipeline/meshik/schema/meshik-constraints-1.schema.json, prose in pipeline/README.md): the one
// reader, checker, resolver and writer, used by the Python pipeline (through meshik._constraints)
// and by the MeshLab plugins.
//
// A file names the rest mesh and the example poses, defines handle groups (vertex indices of the
// rest mesh, or every rest vertex within a radius of a point), and gives per frame the targets of
// the groups (one position per vertex, or a rigid motion of the group's rest positions). A group
// missing from a frame keeps its previous targets (its rest positions before the first frame that
// names it).
//
//   ConstraintDocument document = read_constraint_file("shot.json");   // throws ConstraintError
//   MeshFiles meshes = locate_mesh_files(document);                    // absolute rest/example paths
//   ResolvedConstraints resolved = resolve_constraints(document, rest, num_vertices);
//
// Every error message starts with the file's name, then the JSON path of the element at fault
// ("top level" for the document itself), then the problem:
//   "shot.json: frames[3].targets.head: expected 3 numbers, got a list of 2"
//   "shot.json: not valid JSON: line 4 column 9: syntax error while parsing ..."
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace meshik::constraints {

// A bad constraint file (or one that cannot be read or written); what() is the full message.
class ConstraintError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One problem: the JSON path of the element ("" for the document) and what is wrong with it.
struct Violation {
  std::string path;
  std::string problem;
};

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<double, 9>;  // row-major

// A handle group: vertex indices of the rest mesh, or every rest vertex within `radius` of `near`.
struct HandleGroup {
  std::string name;
  std::vector<std::int64_t> vertices;  // empty for a region
  std::optional<Vec3> near;            // set for a region
  double radius = 0.0;
};

// A group's target in one frame: per-vertex positions, or the rigid motion
// p -> rotation (p - center) + center + translation of the group's rest positions.
struct GroupTarget {
  std::string group;               // the handle group's name
  std::string path;                // its JSON path, for messages: frames[2].targets.head
  bool rigid = false;
  std::vector<double> positions;   // #group by 3 row-major (when not rigid)
  Mat3 rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 translation{0, 0, 0};
  std::optional<Vec3> center;      // none: the centroid of the group's rest positions
};

// One frame: its name (used in output file names) and the targets it sets, in the file's order.
struct Frame {
  std::string name;  // "0001", "0002", ... when the file gives none
  std::vector<GroupTarget> targets;
};

// "regions": spatially varying blend weights. A count of regions clustered from the examples
// (count >= 1), "auto" (automatic), or vertex groups by name (each a list of rest vertex indices;
// vertices in no group form one more region).
struct RegionGroup {
  std::string name;
  std::vector<std::int64_t> vertices;
};
struct RegionSetting {
  std::int64_t count = 1;
  bool automatic = false;
  std::vector<RegionGroup> groups;  // in the file's order; non-empty for vertex groups
};

// A checked constraint file. Mesh file names are as written in the file (see locate_mesh_files);
// options left out of the file are empty.
struct ConstraintDocument {
  std::string source;                      // the file's name as given (starts every message)
  std::string rest;                        // "rest"
  std::vector<std::string> examples;       // "examples" as a list of names
  std::optional<std::string> examples_glob;  // or "examples" as a glob pattern
  std::vector<HandleGroup> handles;        // in the file's order
  std::vector<Frame> frames;
  std::optional<std::string> feature_space;  // "nonlinear" or "linear"
  std::optional<std::string> blend;          // "affine" or "free"
  std::optional<RegionSetting> regions;
  std::optional<double> region_smoothness;
  std::optional<double> weight_regularization;
  std::optional<double> handle_stiffness;  // >= 0; 0 = hard handles
  std::optional<std::int64_t> max_iterations;
  std::optional<double> tolerance;
  double fps = 24.0;
};

// Reads and checks the constraint file at `path`; `path` names it in messages.
// Throws ConstraintError (the first problem) when the file is missing, unreadable, not UTF-8, not
// JSON, has duplicate keys, or breaks a rule of the format.
ConstraintDocument read_constraint_file(const std::string& path);

// Checks constraint-file text; `source` names it in messages (and anchors relative mesh paths).
// Throws ConstraintError with the first problem.
ConstraintDocument parse_constraints(std::string_view text, const std::string& source);

// Every problem of the constraint file at `path` as full messages (empty: the file is good).
// With check_mesh_files, also checks that the rest and example meshes exist (locate_mesh_files).
std::vector<std::string> validate_constraint_file(const std::string& path, bool check_mesh_files);

// The mesh files a document names, as absolute paths with symbolic links resolved.
struct MeshFiles {
  std::string rest;
  std::vector<std::string> examples;  // a glob's matches sorted by their numbers (pose2 before pose10)
};

// Finds the rest and example meshes (relative names are taken from the folder of the document's
// source). A glob skips the rest mesh. Throws ConstraintError for a missing file or an empty glob.
MeshFiles locate_mesh_files(const ConstraintDocument& document);

// Handle groups resolved against a rest mesh.
struct ResolvedConstraints {
  std::vector<std::string> group_names;            // in the file's order
  std::vector<std::vector<std::int64_t>> groups;   // vertex indices of each group
  std::vector<std::int64_t> handles;               // #H: the groups concatenated
  std::vector<double> targets;                     // #frames by #H by 3, row-major, in the order of handles
  std::vector<std::string> frame_names;            // #frames
};

// Resolves the handle groups and the targets of frames 0 .. last_frame (all frames when
// last_frame < 0) against the rest mesh: rest_vertices is #V by 3 row-major. Throws
// ConstraintError for out-of-range indices, empty regions, overlapping groups, or position lists
// whose length differs from their region's size.
ResolvedConstraints resolve_constraints(const ConstraintDocument& document, const double* rest_vertices,
                                        std::int64_t num_vertices, std::int64_t last_frame = -1);

// The 0-based index of the frame named `frame`, or else numbered `frame` ("0", "12").
// Throws ConstraintError when there is none.
std::int64_t find_frame(const ConstraintDocument& document, const std::string& frame);

// One handle group and its targets, for write_constraint_file.
struct GroupPositions {
  std::string name;                    // a non-empty name, not starting with '_'
  std::vector<std::int64_t> vertices;  // #group vertex indices of the rest mesh
  std::vector<double> targets;         // #group by 3 row-major target positions
};

// The optional solver settings of a written file; members left empty are not written (readers
// then use the format's defaults).
struct WrittenSettings {
  std::optional<std::string> feature_space;       // "nonlinear" or "linear"
  std::optional<std::string> blend;               // "affine" or "free"
  std::optional<std::int64_t> regions;            // a region count >= 1, or -1 for "auto"
  std::optional<double> region_smoothness;        // >= 0
  std::optional<double> weight_regularization;    // k >= 0
  std::optional<double> handle_stiffness;         // >= 0; 0 = hard handles
  std::optional<std::int64_t> max_iterations;     // >= 1
};

// Writes a constraint file with one frame named `frame_name` that sets every group's targets:
// "rest" and "examples" are written as given (names relative to the file's folder, or absolute),
// then the members of `settings` that are set. The text is checked by parse_constraints before it
// replaces `path` (written to a temporary file in the same folder, then renamed). Throws
// ConstraintError naming `path` for bad content (no group, a duplicate vertex, non-finite targets,
// a bad frame name or setting, ...) or a failed write.
void write_constraint_file(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                           const std::vector<GroupPositions>& groups, const std::string& frame_name = "0001",
                           const WrittenSettings& settings = {});

// Writes a constraint file with any number of frames: "rest" and "examples" as given, the members
// of `settings` that are set, the handle groups (vertex lists, in order) and the frames in order.
// A frame's target is written as its position list, or for a rigid one as
// {"rotate": {"axis", "degrees", "center"}, "translate"} ("rotate" left out for the identity,
// "center" for an unset centre). Checked and written like write_constraint_file; ConstraintError
// names `path` and the group or frame at fault.
void write_constraint_frames(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
                             const std::vector<HandleGroup>& groups, const std::vector<Frame>& frames,
                             const WrittenSettings& settings = {});

}  // namespace meshik::constraints
