// A geodesic sphere (icosahedron with every face split into frequency^2 triangles, projected
// to the unit sphere) for large benchmark meshes: 20 * frequency^2 triangles.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <tuple>

#include "obj_reader.h"

namespace meshik_bench {

inline TriangleMesh geodesic_sphere(int frequency) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  const Eigen::Vector3d corner[12] = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0},
                                      {0, -1, g}, {0, 1, g},  {0, -1, -g}, {0, 1, -g},
                                      {g, 0, -1}, {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  TriangleMesh mesh;
  // Points shared by neighbouring faces are merged by their rounded position.
  std::map<std::tuple<long long, long long, long long>, int> index_of;
  auto vertex = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p.normalized();
    const auto key = std::make_tuple(std::llround(q.x() * 1e9), std::llround(q.y() * 1e9),
                                     std::llround(q.z() * 1e9));
    const auto found = index_of.find(key);
    if (found != index_of.end()) return found->second;
    const int index = mesh.num_vertices();
    mesh.vertices.insert(mesh.vertices.end(), {q.x(), q.y(), q.z()});
    index_of.emplace(key, index);
    return index;
  };
  for (const auto& f : faces) {
    const Eigen::Vector3d a = corner[f[0]], b = corner[f[1]], c = corner[f[2]];
    auto point = [&](int i, int j) { return vertex(a + (b - a) * i / frequency + (c - a) * j / frequency); };
    for (int i = 0; i < frequency; ++i)
      for (int j = 0; i + j < frequency; ++j) {
        mesh.triangles.insert(mesh.triangles.end(), {point(i, j), point(i + 1, j), point(i, j + 1)});
        if (i + j + 1 < frequency)
          mesh.triangles.insert(mesh.triangles.end(),
                                {point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
      }
  }
  return mesh;
}

}  // namespace meshik_bench
