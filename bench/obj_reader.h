// A tiny Wavefront OBJ reader for the benchmarks and tests: `v x y z` and triangular
// `f a b c` lines only (1-based indices, optional /vt/vn suffixes); everything else is skipped.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace meshik_bench {

struct TriangleMesh {
  std::vector<double> vertices;  // #V by 3 row-major positions
  std::vector<int> triangles;    // #F by 3 row-major 0-based vertex indices
  int num_vertices() const { return static_cast<int>(vertices.size() / 3); }
  int num_triangles() const { return static_cast<int>(triangles.size() / 3); }
};

// Reads `path`. Throws std::runtime_error naming the file and line for a face that is not a
// triangle or an index out of range, or when the file cannot be opened.
inline TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  TriangleMesh mesh;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      double x, y, z;
      if (!(fields >> x >> y >> z))
        throw std::runtime_error(path + ":" + std::to_string(line_number) + ": bad vertex");
      mesh.vertices.insert(mesh.vertices.end(), {x, y, z});
    } else if (tag == "f") {
      std::vector<int> corners;
      for (std::string corner; fields >> corner;) corners.push_back(std::stoi(corner) - 1);
      if (corners.size() != 3)
        throw std::runtime_error(path + ":" + std::to_string(line_number) + ": face with " +
                                 std::to_string(corners.size()) + " corners, expected 3");
      mesh.triangles.insert(mesh.triangles.end(), corners.begin(), corners.end());
    }
  }
  for (size_t k = 0; k < mesh.triangles.size(); ++k)
    if (mesh.triangles[k] < 0 || mesh.triangles[k] >= mesh.num_vertices())
      throw std::runtime_error(path + ": triangle " + std::to_string(k / 3) +
                               " has a vertex index out of range");
  return mesh;
}

}  // namespace meshik_bench
