// The conformance fixtures through the C++ constraint-file library: every bad file is refused with
// "<path>: <expected message>", every good file resolves to the expected handles and targets
// (tests/python/test_constraints_conformance.py runs the same fixtures through Python, the plugin
// and the JSON Schema).
#include "constraints_fixtures.h"
#include "meshik/constraints/constraint_file.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mc = meshik::constraints;
using namespace meshik::constraints::testing;

namespace {

// Reads, locates the meshes and resolves `path` on the rest grid, as the pipeline does.
mc::ResolvedConstraints load_and_resolve(const std::string& path, const std::vector<double>& rest) {
  const mc::ConstraintDocument document = mc::read_constraint_file(path);
  mc::locate_mesh_files(document);
  return mc::resolve_constraints(document, rest.data(), static_cast<std::int64_t>(rest.size() / 3));
}

TEST(ConstraintsConformance, EveryBadFileIsRefusedWithItsMessage) {
  const auto expected = expected_results();
  const std::vector<double> rest = rest_vertices();
  ASSERT_GE(expected["bad"].size(), 40u);
  for (const auto& [name, result] : expected["bad"].items()) {
    const std::string path = fixtures_dir() + "/bad/" + name;
    try {
      load_and_resolve(path, rest);
      ADD_FAILURE() << name << " was accepted";
    } catch (const mc::ConstraintError& error) {
      EXPECT_EQ(std::string(error.what()), path + ": " + result["message"].get<std::string>()) << name;
    }
  }
}

TEST(ConstraintsConformance, EveryGoodFileResolvesToTheExpectedTargets) {
  const auto expected = expected_results();
  const std::vector<double> rest = rest_vertices();
  ASSERT_GE(expected["good"].size(), 6u);
  for (const auto& [name, result] : expected["good"].items()) {
    const mc::ResolvedConstraints resolved = load_and_resolve(fixtures_dir() + "/good/" + name, rest);
    EXPECT_EQ(resolved.frame_names, result["frame_names"].get<std::vector<std::string>>()) << name;
    EXPECT_EQ(resolved.handles, result["handles"].get<std::vector<std::int64_t>>()) << name;
    std::vector<double> targets;
    for (const auto& frame : result["targets"])
      for (const auto& position : frame)
        for (double coordinate : position) targets.push_back(coordinate);
    ASSERT_EQ(resolved.targets.size(), targets.size()) << name;
    for (std::size_t i = 0; i < targets.size(); ++i)
      EXPECT_NEAR(resolved.targets[i], targets[i], 1e-12) << name << " coordinate " << i;
  }
}

TEST(ConstraintsConformance, ValidateReportsEveryBadFileAndNoGoodOne) {
  const auto expected = expected_results();
  for (const auto& [name, result] : expected["good"].items())
    EXPECT_EQ(mc::validate_constraint_file(fixtures_dir() + "/good/" + name, true), std::vector<std::string>{}) << name;
  for (const auto& [name, result] : expected["bad"].items()) {
    const std::string path = fixtures_dir() + "/bad/" + name;
    const auto problems = mc::validate_constraint_file(path, true);
    if (result["stage"] == "resolve") {  // found only on the rest mesh: validate checks format and files
      EXPECT_EQ(problems, std::vector<std::string>{}) << name;
      continue;
    }
    ASSERT_FALSE(problems.empty()) << name;
    EXPECT_EQ(problems.front(), path + ": " + result["message"].get<std::string>()) << name;
  }
}

}  // namespace
