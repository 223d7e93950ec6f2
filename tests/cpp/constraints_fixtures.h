// The conformance fixtures of the constraint format (tests/constraints_conformance) for the C++
// tests: the folder, its manifest, the grid's rest vertices and file reading.
#pragma once

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace meshik::constraints::testing {

// The fixtures folder (set by tests/CMakeLists.txt).
inline std::string fixtures_dir() { return MESHIK_CONFORMANCE_DIR; }

// The bytes of a file.
inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// expected.json: {"bad": {name: {"message", "structural"}}, "good": {name: {"frame_names", "handles", "targets"}}}.
inline nlohmann::json expected_results() { return nlohmann::json::parse(read_text(fixtures_dir() + "/expected.json")); }

// #V by 3 row-major vertices of the fixtures' rest mesh (the "v x y z" lines of grid/rest.obj).
inline std::vector<double> rest_vertices() {
  std::ifstream in(fixtures_dir() + "/grid/rest.obj");
  std::vector<double> vertices;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream fields(line.substr(2));
    double x, y, z;
    fields >> x >> y >> z;
    vertices.insert(vertices.end(), {x, y, z});
  }
  return vertices;
}

}  // namespace meshik::constraints::testing
