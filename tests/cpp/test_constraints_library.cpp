// The constraint-file library beyond the fixtures: syntax positions, duplicate keys, nesting,
// number wording, every problem at once, frame lookup, and the one-frame writer.
#include "meshik/constraints/constraint_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

namespace mc = meshik::constraints;
namespace fs = std::filesystem;

namespace {

const char* const kHead =
    R"({"format": "meshik-constraints", "version": 1, "rest": "rest.obj", "examples": ["a.obj"], )";

// The ConstraintError message parse_constraints gives for `text` (named "t.json"), or "" when it passes.
std::string parse_error(const std::string& text) {
  try {
    mc::parse_constraints(text, "t.json");
  } catch (const mc::ConstraintError& error) {
    return error.what();
  }
  return "";
}

// A fresh, empty folder for files.
fs::path scratch_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("meshik_constraints_" + name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ConstraintLibrary, SyntaxErrorsGiveLineAndColumnInCharacters) {
  EXPECT_EQ(parse_error("{\n \"\xc4\xa7\": x}").rfind("t.json: not valid JSON: line 2 column 7: ", 0), 0u)
      << parse_error("{\n \"\xc4\xa7\": x}");
  EXPECT_EQ(parse_error("").rfind("t.json: not valid JSON: line 1 column 1: ", 0), 0u);
  EXPECT_NE(parse_error("[1e400]").find("not valid JSON: line 1 column 6: number overflow"), std::string::npos)
      << parse_error("[1e400]");
}

TEST(ConstraintLibrary, DuplicateKeysAreRefusedWithTheirPath) {
  EXPECT_EQ(parse_error(std::string(kHead) + R"("handles": {"a": [1], "b": [2], "a": [3]}, "frames": [{}]})"),
            "t.json: handles.a: duplicate key");
  EXPECT_EQ(parse_error(std::string(kHead) + R"("handles": {"a": [1]}, "frames": [{}, {"targets": {"a": [[0,0,0]], "a": 1}}]})"),
            "t.json: frames[1].targets.a: duplicate key");
}

TEST(ConstraintLibrary, DeepNestingIsRefusedWithoutRecursion) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  EXPECT_EQ(parse_error(deep), "t.json: JSON nested too deeply");
}

TEST(ConstraintLibrary, NumbersAreWrittenAsInTheFile) {
  const auto version = [](const std::string& literal) {
    return parse_error(R"({"format": "meshik-constraints", "rest": "r", "examples": ["a"], "handles": {"a": [1]},
                       "frames": [{}], "version": )" + literal + "}");
  };
  EXPECT_EQ(version("2.5"), "t.json: version: expected an integer version, got the number 2.5");
  EXPECT_EQ(version("1e-5"), "t.json: version: expected an integer version, got the number 1e-05");
  EXPECT_EQ(version("1E16"), "t.json: version: expected an integer version, got the number 1e+16");
  EXPECT_EQ(version("100.0"), "t.json: version: expected an integer version, got the number 100.0");
  EXPECT_EQ(version("-0"), "t.json: version: expected an integer version >= 1, got 0");
  EXPECT_EQ(version("123456789012345678901234"),
            "t.json: version: expected an integer version, got 123456789012345678901234, which is too large");
  EXPECT_EQ(version("\"" + std::string(41, 'x') + "\""), "t.json: version: expected an integer version, got a long string");
}

TEST(ConstraintLibrary, ValidateReportsEveryProblem) {
  const fs::path dir = scratch_dir("validate");
  const fs::path path = dir / "many.json";
  std::ofstream(path) << R"({"format": "other", "version": 1, "rest": "", "examples": [],
      "handles": {"a": [0, 0], "b": {"near": [0, 0, 0], "radius": 0}},
      "frames": [{"name": "x/y", "targets": {"c": [], "b": 5}}], "fps": -1})";
  const std::vector<std::string> problems = mc::validate_constraint_file(path.string(), true);
  const std::string p = path.string() + ": ";
  EXPECT_EQ(problems, (std::vector<std::string>{
                          p + "format: expected \"meshik-constraints\", got \"other\"",
                          p + "rest: expected a non-empty string",
                          p + "examples: expected a non-empty list",
                          p + "handles.a[1]: vertex 0 is already a handle earlier in this group",
                          p + "handles.b.radius: expected a number > 0, got 0",
                          p + "frames[0].name: \"x/y\" cannot be a file name: use letters, digits, \".\", \"_\", \"-\" (at most 100)",
                          p + "frames[0].targets.c: no handle group named \"c\" (groups: \"a\", \"b\")",
                          p + "fps: expected a number > 0, got -1"}));
  fs::remove_all(dir);
}

TEST(ConstraintLibrary, ValidateReportsEveryMissingMesh) {
  const fs::path dir = scratch_dir("meshes");
  std::ofstream(dir / "rest.obj") << "v 0 0 0\n";
  std::ofstream(dir / "shot.json") << kHead << R"("handles": {"a": [0]}, "frames": [{}]})";
  std::ofstream(dir / "three.json") << R"({"format": "meshik-constraints", "version": 1, "rest": "none.obj",
      "examples": ["rest.obj", "b.obj", "c.obj"], "handles": {"a": [0]}, "frames": [{}]})";
  const std::string p = (dir / "three.json").string() + ": ";
  EXPECT_EQ(mc::validate_constraint_file((dir / "three.json").string(), true),
            (std::vector<std::string>{p + "rest: mesh file not found: " + (dir / "none.obj").string(),
                                      p + "examples[1]: mesh file not found: " + (dir / "b.obj").string(),
                                      p + "examples[2]: mesh file not found: " + (dir / "c.obj").string()}));
  EXPECT_EQ(mc::validate_constraint_file((dir / "three.json").string(), false), std::vector<std::string>{});
  const std::string shot = (dir / "shot.json").string();
  EXPECT_EQ(mc::validate_constraint_file(shot, true),
            std::vector<std::string>{shot + ": examples[0]: mesh file not found: " + (dir / "a.obj").string()});
  std::ofstream(dir / "a.obj") << "v 0 0 0\n";
  EXPECT_EQ(mc::validate_constraint_file(shot, true), std::vector<std::string>{});
  const mc::MeshFiles files = mc::locate_mesh_files(mc::read_constraint_file(shot));
  EXPECT_EQ(files.rest, (dir / "rest.obj").string());
  EXPECT_EQ(files.examples, std::vector<std::string>{(dir / "a.obj").string()});
  fs::remove_all(dir);
}

TEST(ConstraintLibrary, GlobsSortByNumberAndSkipTheRestMesh) {
  const fs::path dir = scratch_dir("glob");
  for (const char* name : {"rest.obj", "pose10.obj", "pose2.obj", "pose02b.obj", "pose1.obj"}) std::ofstream(dir / name) << "v\n";
  std::ofstream(dir / "shot.json") << R"({"format": "meshik-constraints", "version": 1, "rest": "rest.obj",
      "examples": "*.obj", "handles": {"a": [0]}, "frames": [{}]})";
  const mc::MeshFiles files = mc::locate_mesh_files(mc::read_constraint_file((dir / "shot.json").string()));
  std::vector<std::string> names;
  for (const std::string& path : files.examples) names.push_back(fs::path(path).filename().string());
  EXPECT_EQ(names, (std::vector<std::string>{"pose1.obj", "pose2.obj", "pose02b.obj", "pose10.obj"}));
  fs::remove_all(dir);
}

TEST(ConstraintLibrary, MissingAndUnreadableFiles) {
  const fs::path dir = scratch_dir("missing");
  EXPECT_EQ(mc::validate_constraint_file((dir / "none.json").string(), true),
            std::vector<std::string>{(dir / "none.json").string() + ": constraint file not found"});
  std::ofstream(dir / "binary.json", std::ios::binary) << "{\"a\": \"\xff\"}";
  EXPECT_THROW(mc::read_constraint_file((dir / "binary.json").string()), mc::ConstraintError);
  EXPECT_EQ(mc::validate_constraint_file((dir / "binary.json").string(), true),
            std::vector<std::string>{(dir / "binary.json").string() + ": not UTF-8 text (byte 7)"});
  fs::remove_all(dir);
}

TEST(ConstraintLibrary, FramesAreFoundByNameThenNumber) {
  const mc::ConstraintDocument document = mc::parse_constraints(
      std::string(kHead) + R"("handles": {"a": [1]}, "frames": [{"name": "1"}, {"name": "walk"}, {}]})", "t.json");
  EXPECT_EQ(mc::find_frame(document, "walk"), 1);
  EXPECT_EQ(mc::find_frame(document, "1"), 0);  // a name first
  EXPECT_EQ(mc::find_frame(document, "2"), 2);
  try {
    mc::find_frame(document, "3");
    FAIL() << "frame 3 found";
  } catch (const mc::ConstraintError& error) {
    EXPECT_EQ(std::string(error.what()),
              "t.json: frames: no frame named or numbered \"3\" (the file has 3 frames, numbered from 0, named 1 ... 0003)");
  }
}

TEST(ConstraintLibrary, WrittenFilesReadBackToTheSameTargets) {
  const fs::path dir = scratch_dir("write");
  const std::string path = (dir / "saved.json").string();
  const std::vector<mc::GroupPositions> groups{{"left foot", {3, 0}, {0.1, 0.2, 0.3, 1.0 / 3.0, -2e-17, 5e300}},
                                               {"tip", {7}, {1, 2, 3}}};
  mc::write_constraint_file(path, "rest.obj", {"example_1.obj"}, groups, "pose-1");
  const mc::ConstraintDocument document = mc::read_constraint_file(path);
  ASSERT_EQ(document.frames.size(), 1u);
  EXPECT_EQ(document.frames[0].name, "pose-1");
  EXPECT_EQ(document.rest, "rest.obj");
  const std::vector<double> rest(3 * 8, 0.0);
  const mc::ResolvedConstraints resolved = mc::resolve_constraints(document, rest.data(), 8);
  EXPECT_EQ(resolved.handles, (std::vector<std::int64_t>{3, 0, 7}));
  EXPECT_EQ(resolved.targets, (std::vector<double>{0.1, 0.2, 0.3, 1.0 / 3.0, -2e-17, 5e300, 1, 2, 3}));  // exact
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporary left
  fs::remove_all(dir);
}

TEST(ConstraintLibrary, WrittenBlendAndRegionSettingsReadBack) {
  const fs::path dir = scratch_dir("write_regions");
  const std::string path = (dir / "saved.json").string();
  mc::WrittenSettings settings;
  settings.blend = "free";
  settings.regions = 4;
  settings.region_smoothness = 0.25;
  settings.handle_stiffness = 2.5;
  mc::write_constraint_file(path, "rest.obj", {"example_1.obj"}, {{"tip", {7}, {1, 2, 3}}}, "pose-1", settings);
  mc::ConstraintDocument document = mc::read_constraint_file(path);
  EXPECT_EQ(document.handle_stiffness, 2.5);
  EXPECT_EQ(document.blend, "free");
  ASSERT_TRUE(document.regions.has_value());
  EXPECT_EQ(document.regions->count, 4);
  EXPECT_FALSE(document.regions->automatic);
  EXPECT_EQ(document.region_smoothness, 0.25);
  settings.regions = -1;
  mc::write_constraint_file(path, "rest.obj", {"example_1.obj"}, {{"tip", {7}, {1, 2, 3}}}, "pose-1", settings);
  document = mc::read_constraint_file(path);
  ASSERT_TRUE(document.regions.has_value());
  EXPECT_TRUE(document.regions->automatic);
  settings.handle_stiffness.reset();  // left out: the file keeps hard handles
  mc::write_constraint_file(path, "rest.obj", {"example_1.obj"}, {{"tip", {7}, {1, 2, 3}}}, "pose-1", settings);
  EXPECT_FALSE(mc::read_constraint_file(path).handle_stiffness.has_value());
  settings.handle_stiffness = std::numeric_limits<double>::infinity();
  try {
    mc::write_constraint_file(path, "rest.obj", {"example_1.obj"}, {{"tip", {7}, {1, 2, 3}}}, "pose-1", settings);
    FAIL() << "an infinite handle stiffness was written";
  } catch (const mc::ConstraintError& error) {
    EXPECT_EQ(std::string(error.what()), path + ": handle_stiffness: expected a finite number >= 0");
  }
  fs::remove_all(dir);
}

TEST(ConstraintLibrary, HandleStiffnessMustBeAFiniteNumberAtLeastZero) {
  const std::string body = R"("handles": {"a": [1]}, "frames": [{}], "handle_stiffness": )";
  EXPECT_EQ(parse_error(std::string(kHead) + body + "-0.5}"), "t.json: handle_stiffness: expected a number >= 0, got -0.5");
  // JSON has no non-finite numbers: one beyond doubles is refused by the parser, naming the file.
  EXPECT_EQ(parse_error(std::string(kHead) + body + "1e999}").rfind("t.json: not valid JSON: ", 0), 0u);
  EXPECT_EQ(parse_error(std::string(kHead) + body + "\"soft\"}"),
            "t.json: handle_stiffness: expected a number, got \"soft\"");
  EXPECT_EQ(mc::parse_constraints(std::string(kHead) + body + "0}", "t.json").handle_stiffness, 0.0);
}

TEST(ConstraintLibrary, WriterRefusesBadContentAndKeepsTheOldFile) {
  const fs::path dir = scratch_dir("write_bad");
  const std::string path = (dir / "saved.json").string();
  std::ofstream(path) << "old";
  const auto refused = [&](const std::vector<mc::GroupPositions>& groups, const std::string& frame = "0001") {
    try {
      mc::write_constraint_file(path, "rest.obj", {"a.obj"}, groups, frame);
    } catch (const mc::ConstraintError& error) {
      return std::string(error.what());
    }
    return std::string("written");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refused({{"g", {1}, {0, nan, 0}}}), path + ": handle group \"g\": the target of vertex 1 is not finite");
  EXPECT_EQ(refused({{"g", {1, 2}, {0, 0, 0}}}),
            path + ": handle group \"g\": 2 vertices but 3 target coordinates (expected 3 per vertex)");
  EXPECT_EQ(refused({{"g", {1}, {0, 0, 0}}, {"h", {1}, {0, 0, 0}}}),
            path + ": handles.h[0]: vertex 1 is already a handle in handle group \"g\"");
  EXPECT_EQ(refused({}), path + ": handles: expected at least one handle group");
  EXPECT_EQ(refused({{"g", {1}, {0, 0, 0}}}, "a/b").rfind(path + ": frames[0].name: \"a/b\" cannot be a file name", 0), 0u);
  std::ifstream in(path);
  std::string kept;
  in >> kept;
  EXPECT_EQ(kept, "old");
  fs::remove_all(dir);
}

}  // namespace
