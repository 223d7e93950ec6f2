// Input checks with messages that name the offending vertex, triangle, example or handle.
#include "input_validation.h"

#include "meshik/thread_limit.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace meshik {

namespace {

// A triangle whose doubled area is below this fraction of its longest edge squared has no
// usable frame (its deformation gradient is undefined).
constexpr double kZeroAreaRatio = 1e-12;

bool finite3(const double* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// The largest absolute coordinate of a triangle's corners t[0..2], as short text ("1e+300").
std::string magnitude_text(const double* vertices, const int* t) {
  double largest = 0.0;
  for (int q = 0; q < 3; ++q)
    for (int d = 0; d < 3; ++d) largest = std::max(largest, std::abs(vertices[3 * static_cast<size_t>(t[q]) + d]));
  std::ostringstream text;
  text.precision(3);
  text << largest;
  return text.str();
}

Eigen::Vector3d point(const double* vertices, int v) {
  return Eigen::Vector3d(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
}

}  // namespace

void validate_rest_mesh(const MeshView& rest) {
  if (rest.num_vertices <= 0 || rest.vertices == nullptr)
    throw InputError("the rest mesh has no vertices");
  if (rest.num_triangles <= 0 || rest.triangles == nullptr)
    throw InputError("the rest mesh has no triangles");
  for (int v = 0; v < rest.num_vertices; ++v)
    if (!finite3(rest.vertices + 3 * v))
      throw InputError("rest vertex " + std::to_string(v) + " has a non-finite coordinate");
  const int n = rest.num_vertices;
  for (int j = 0; j < rest.num_triangles; ++j) {
    const int* t = rest.triangles + 3 * j;
    for (int q = 0; q < 3; ++q)
      if (t[q] < 0 || t[q] >= n)
        throw InputError("triangle " + std::to_string(j) + " has vertex index " +
                         std::to_string(t[q]) + " out of range [0, " + std::to_string(n) + ")");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw InputError("triangle " + std::to_string(j) + " repeats a vertex (" +
                       std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ")");
    const Eigen::Vector3d a = point(rest.vertices, t[0]);
    const Eigen::Vector3d e1 = point(rest.vertices, t[1]) - a;
    const Eigen::Vector3d e2 = point(rest.vertices, t[2]) - a;
    const double longest =
        std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    if (!std::isfinite(longest) || !std::isfinite(e1.cross(e2).norm()))
      throw InputError("triangle " + std::to_string(j) + " is too large to measure in double precision (a corner's "
                       "coordinates reach " + magnitude_text(rest.vertices, t) + ")");
    if (!(e1.cross(e2).norm() > kZeroAreaRatio * longest))
      throw InputError("triangle " + std::to_string(j) + " has zero area in the rest mesh");
  }
}

void validate_examples(const std::vector<const double*>& examples, int num_vertices) {
  for (size_t i = 0; i < examples.size(); ++i) {
    if (examples[i] == nullptr) throw InputError("example " + std::to_string(i) + " is missing");
    for (int v = 0; v < num_vertices; ++v)
      if (!finite3(examples[i] + 3 * v))
        throw InputError("example " + std::to_string(i) + " vertex " + std::to_string(v) +
                         " has a non-finite coordinate");
  }
}

void validate_handles(const std::vector<int>& handles, int num_vertices,
                      const VertexComponents& components, const std::vector<int>& internal_of_vertex) {
  if (handles.empty()) throw InputError("no handles: at least one vertex must be constrained");
  auto component_of = [&](int v) { return components.component_of_vertex[internal_of_vertex[v]]; };
  std::vector<int> handle_of_vertex(num_vertices, -1);
  std::vector<char> anchored(components.count, 0);
  for (size_t h = 0; h < handles.size(); ++h) {
    const int v = handles[h];
    const std::string name = "handle " + std::to_string(h) + " (vertex " + std::to_string(v) + ")";
    if (v < 0 || v >= num_vertices)
      throw InputError(name + " is out of range [0, " + std::to_string(num_vertices) + ")");
    if (handle_of_vertex[v] >= 0)
      throw InputError(name + " repeats handle " + std::to_string(handle_of_vertex[v]));
    handle_of_vertex[v] = static_cast<int>(h);
    if (component_of(v) >= 0) anchored[component_of(v)] = 1;
  }
  for (int v = 0; v < num_vertices; ++v) {
    const int c = component_of(v);
    if (c >= 0 && !anchored[c]) {
      int size = 0;
      for (int u : components.component_of_vertex) size += (u == c);
      throw InputError("the connected component containing vertex " + std::to_string(v) + " (" +
                       std::to_string(size) +
                       " vertices) has no handle: its position would be undetermined");
    }
  }
}

void validate_options(const SolverOptions& options) {
  if (!(std::isfinite(options.weight_regularization) && options.weight_regularization >= 0.0))
    throw InputError("weight_regularization must be finite and >= 0, got " +
                     std::to_string(options.weight_regularization));
  if (!(std::isfinite(options.tolerance) && options.tolerance >= 0.0))
    throw InputError("tolerance must be finite and >= 0, got " +
                     std::to_string(options.tolerance));
  if (options.threads < 0 || options.threads > kMaxThreads)
    throw InputError("threads must be 0 (all cores) or a count from 1 to " + std::to_string(kMaxThreads) + ", got " +
                     std::to_string(options.threads));
  if (options.max_iterations < 0)
    throw InputError("max_iterations must be >= 0, got " +
                     std::to_string(options.max_iterations));
  if (options.regions < 1 && options.regions != kAutomaticRegions)
    throw InputError("regions must be a count >= 1 or automatic, got " + std::to_string(options.regions));
  if (!(std::isfinite(options.region_smoothness) && options.region_smoothness >= 0.0))
    throw InputError("region_smoothness must be finite and >= 0, got " + std::to_string(options.region_smoothness));
  if (!(std::isfinite(options.handle_stiffness) && options.handle_stiffness >= 0.0))
    throw InputError("handle_stiffness must be finite and >= 0 (0: hard handles), got " +
                     std::to_string(options.handle_stiffness));
}

void validate_finite(const double* values, int count, const char* what) {
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(values[i]))
      throw InputError(std::string(what) + " " + std::to_string(i) + " is not finite");
}

void validate_targets(const double* targets, const std::vector<int>& handles) {
  if (targets == nullptr) throw InputError("no target positions given for the handles");
  for (size_t h = 0; h < handles.size(); ++h)
    if (!finite3(targets + 3 * h))
      throw InputError("target " + std::to_string(h) + " (handle vertex " +
                       std::to_string(handles[h]) + ") has a non-finite coordinate");
}

void validate_pose_finite(const SolveResult& result, const double* targets, const std::vector<int>& handles) {
  const auto finite = [](const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
  };
  if (finite(result.vertices) && finite(result.weights) && std::isfinite(result.residual)) return;
  size_t farthest = 0;
  double largest = -1.0;
  for (size_t h = 0; h < handles.size(); ++h)
    for (int k = 0; k < 3; ++k)
      if (std::abs(targets[3 * h + k]) > largest) largest = std::abs(targets[3 * h + k]), farthest = h;
  std::ostringstream target;
  target.precision(3);
  target << "(" << targets[3 * farthest] << ", " << targets[3 * farthest + 1] << ", " << targets[3 * farthest + 2] << ")";
  throw InputError("the pose leaves the finite range of double precision: target " + std::to_string(farthest) +
                   " (handle vertex " + std::to_string(handles[farthest]) + ") at " + target.str() +
                   " is too far out for this mesh");
}

}  // namespace meshik
