// Deformation-aware decimation of an example set with OpenMesh's decimater (see decimate.h).
#include "meshik/decimate.h"

#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <limits>

#include "decimation_mesh.h"
#include "quadric.h"
#include "triangle_check.h"
#include "triangle_soundness.h"
#include "pose_distance_module.h"

namespace meshik {
namespace {

using decimation::Mesh;
using decimation::Poses;
using decimation::Quadric;
using decimation::Vec;

// Decimater module: priority = quadric error summed over all poses at the kept vertex;
// illegal when a remaining triangle would flip (beyond a limit) or degenerate in any pose.
// Vertex handles keep their original index during decimation (no garbage collection), so
// vh.idx() is the original vertex id throughout.
class ModPoseQuadric : public OpenMesh::Decimater::ModBaseT<Mesh> {
 public:
  typedef OpenMesh::Decimater::ModHandleT<ModPoseQuadric> Handle;
  typedef OpenMesh::Decimater::ModBaseT<Mesh> Base;
  DECIMATER_MODNAME(PoseQuadric)

  // DecimaterT::add constructs modules from the mesh alone: configure() sets the rest.
  explicit ModPoseQuadric(Mesh& mesh) : Base(mesh, false) {}

  // poses: every pose's positions (kept alive by the caller); the normal-change limit in degrees.
  void configure(const Poses* poses, double max_normal_change_degrees) {
    poses_ = poses;
    min_cos_ = std::cos(max_normal_change_degrees * M_PI / 180.0);
  }

  // Quadrics of every vertex in every pose: area-weighted face planes, plus planes through
  // boundary edges perpendicular to their face, so that open borders keep their shape.
  void initialize() override {
    Mesh& m = mesh();
    const int n = poses_->num_vertices;
    quadrics_.assign(static_cast<size_t>(poses_->count()) * n, Quadric());
    for (int p = 0; p < poses_->count(); ++p) {
      for (auto fh : m.faces()) {
        std::array<int, 3> v;
        int i = 0;
        for (auto vh : m.fv_range(fh)) v[i++] = vh.idx();
        decimation::add_triangle_plane(poses_->at(p, v[0]), poses_->at(p, v[1]), poses_->at(p, v[2]), quadric(p, v[0]),
                                       quadric(p, v[1]), quadric(p, v[2]));
      }
      for (auto heh : m.halfedges()) {
        if (!m.is_boundary(heh)) continue;
        const int from = m.from_vertex_handle(heh).idx(), to = m.to_vertex_handle(heh).idx();
        const auto face = m.face_handle(m.opposite_halfedge_handle(heh));
        std::array<int, 3> v;
        int i = 0;
        for (auto vh : m.fv_range(face)) v[i++] = vh.idx();
        decimation::add_border_plane(poses_->at(p, from), poses_->at(p, to), poses_->at(p, v[0]), poses_->at(p, v[1]),
                                     poses_->at(p, v[2]), quadric(p, from), quadric(p, to));
      }
    }
    parent_.resize(n);
    for (int v = 0; v < n; ++v) parent_[v] = v;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    const int v0 = ci.v0.idx(), v1 = ci.v1.idx();
    double error = 0.0;
    for (int p = 0; p < poses_->count(); ++p) {
      Quadric q = quadric(p, v0);
      q += quadric(p, v1);
      error += q.error(poses_->at(p, v1));
    }
    if (!keeps_triangles_sound(ci)) return float(Base::ILLEGAL_COLLAPSE);
    return float(std::max(error, 0.0));
  }

  void postprocess_collapse(const CollapseInfo& ci) override {
    const int v0 = ci.v0.idx(), v1 = ci.v1.idx();
    for (int p = 0; p < poses_->count(); ++p) quadric(p, v1) += quadric(p, v0);
    parent_[v0] = v1;
  }

  // For each original vertex, the vertex it was last collapsed onto (itself if never).
  const std::vector<int>& parents() const { return parent_; }

 private:
  Quadric& quadric(int pose, int vertex) { return quadrics_[static_cast<size_t>(pose) * poses_->num_vertices + vertex]; }

  // Whether moving v0 onto v1 leaves every remaining triangle around v0 non-degenerate and
  // within the normal-change limit, in every pose.
  bool keeps_triangles_sound(const CollapseInfo& ci) {
    Mesh& m = mesh();
    for (auto fh : m.vf_range(ci.v0)) {
      if (fh == ci.fl || fh == ci.fr) continue;  // removed by the collapse
      std::array<int, 3> v;
      int i = 0, moved = 0;
      for (auto vh : m.fv_range(fh)) {
        if (vh == ci.v0) moved = i;
        v[i++] = vh.idx();
      }
      for (int p = 0; p < poses_->count(); ++p) {
        const std::array<Vec, 3> corner = {poses_->at(p, v[0]), poses_->at(p, v[1]), poses_->at(p, v[2])};
        if (!decimation::moved_triangle_is_sound(corner, moved, poses_->at(p, ci.v1.idx()), min_cos_)) return false;
      }
    }
    return true;
  }

  const Poses* poses_ = nullptr;
  double min_cos_ = 0.5;
  std::vector<Quadric> quadrics_;
  std::vector<int> parent_;
};

// OpenMesh mesh of the rest pose (after check_triangles); throws InputError for a triangle that
// cannot join a manifold mesh (a non-manifold vertex).
Mesh build_mesh(const MeshView& rest) {
  decimation::check_triangles(rest);
  Mesh mesh;
  std::vector<Mesh::VertexHandle> handles(rest.num_vertices);
  for (int v = 0; v < rest.num_vertices; ++v) {
    const double* p = rest.vertices + 3 * static_cast<size_t>(v);
    handles[v] = mesh.add_vertex(Mesh::Point(p[0], p[1], p[2]));
  }
  omerr().disable();  // add_face reports complex vertices on stderr: we throw instead
  for (int f = 0; f < rest.num_triangles; ++f) {
    const int* t = rest.triangles + 3 * static_cast<size_t>(f);
    if (!mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid()) {
      omerr().enable();
      throw InputError("triangle " + std::to_string(f) +
                       " makes the mesh non-manifold (a complex vertex); the OpenMesh simplifier needs a manifold mesh");
    }
  }
  omerr().enable();
  return mesh;
}

// How many triangles of the mesh are not deleted.
size_t remaining_triangles(const Mesh& mesh) {
  size_t count = 0;
  for (auto fh : mesh.faces()) count += mesh.status(fh).deleted() ? 0 : 1;
  return count;
}

}  // namespace

DecimationResult decimate_example_set(const MeshView& rest, const std::vector<const double*>& examples,
                                      const std::vector<int>& locked, int target_triangles,
                                      double max_normal_change_degrees, const DistanceBound& bound) {
  decimation::check_request(rest.num_vertices, locked, target_triangles, bound);
  Mesh mesh = build_mesh(rest);
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  for (int v : locked) mesh.status(mesh.vertex_handle(v)).set_locked(true);
  Poses poses;
  poses.num_vertices = rest.num_vertices;
  poses.positions.push_back(rest.vertices);
  poses.positions.insert(poses.positions.end(), examples.begin(), examples.end());

  OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
  ModPoseQuadric::Handle module;
  decimater.add(module);
  decimater.module(module).configure(&poses, max_normal_change_degrees);
  decimation::ModPoseDistance::Handle distance_guard;
  decimater.add(distance_guard);
  DecimationResult result;
  result.bound = bound.max_distance;
  decimater.module(distance_guard).configure(&poses, result.bound);
  decimater.initialize();
  decimater.decimate_to_faces(0, static_cast<size_t>(target_triangles));
  // each call rebuilds the collapse queue from the current mesh under the relaxed bound
  while (remaining_triangles(mesh) > static_cast<size_t>(target_triangles) && !std::isinf(result.bound)) {
    ++result.relaxations;
    const double least_refused = decimater.module(distance_guard).least_refused();
    result.bound = result.relaxations > bound.max_relaxations
                       ? std::numeric_limits<double>::infinity()
                       : std::max(result.bound * bound.relax_factor, least_refused);
    decimater.module(distance_guard).configure(&poses, result.bound);
    // OpenMesh counts the deleted triangles too (no garbage collection): aim at the same remainder
    decimater.decimate_to_faces(0, mesh.n_faces() - (remaining_triangles(mesh) - static_cast<size_t>(target_triangles)));
  }

  result.worst_distance = decimater.module(distance_guard).worst_distance();
  std::vector<int> new_index(rest.num_vertices, -1);
  for (int v = 0; v < rest.num_vertices; ++v) {
    if (!mesh.status(mesh.vertex_handle(v)).deleted()) {
      new_index[v] = static_cast<int>(result.kept_vertices.size());
      result.kept_vertices.push_back(v);
    }
  }
  for (auto fh : mesh.faces()) {
    if (mesh.status(fh).deleted()) continue;
    for (auto vh : mesh.fv_range(fh)) result.triangles.push_back(new_index[vh.idx()]);
  }
  const std::vector<int>& parents = decimater.module(module).parents();
  result.vertex_map.resize(rest.num_vertices);
  for (int v = 0; v < rest.num_vertices; ++v) {
    int root = v;
    while (parents[root] != root) root = parents[root];
    result.vertex_map[v] = new_index[root];
  }
  return result;
}

}  // namespace meshik
