// meshik._core.decimate and decimate_fast: the two decimators of cpp_core/decimate (OpenMesh's and
// our own) for Python, numpy in and out.
// Registered by bind_decimate() (decimate_module.h), which the module definition (core_module.cpp) calls.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/vector.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "decimate_module.h"
#include "meshik/decimate.h"
#include "owned_array.h"

namespace nb = nanobind;

namespace {

using Positions = nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
using Triangles = nb::ndarray<const int, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
using Indices = nb::ndarray<const int, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using IntArray = nb::ndarray<nb::numpy, int>;

// A numpy int32 array owning `values`, with the given shape (rows, or rows by columns).
IntArray to_numpy(std::vector<int>&& values, size_t rows, size_t columns) {
  if (columns == 0) return meshik_bindings::owned_array(std::move(values), {rows});
  return meshik_bindings::owned_array(std::move(values), {rows, columns});
}

// Runs `decimator` (decimate_example_set or a lambda around decimate_example_set_fast) on numpy
// arrays: rest #V by 3, triangles #F by 3, examples each #V by 3, locked #L; the rest as in
// meshik/decimate.h. Returns (kept_vertices #S, triangles #SF by 3, vertex_map #V, worst_distance,
// bound, relaxations).
template <class Decimator>
nb::tuple run_decimator(Decimator decimator, Positions rest, Triangles triangles, const std::vector<Positions>& examples,
                        Indices locked, int target_triangles, double max_normal_change_degrees, double max_distance,
                        double relax_factor, int max_relaxations) {
  const int num_vertices = static_cast<int>(rest.shape(0));
  std::vector<const double*> example_pointers;
  for (size_t i = 0; i < examples.size(); ++i) {
    if (static_cast<int>(examples[i].shape(0)) != num_vertices)
      throw meshik::InputError("example " + std::to_string(i) + " has " + std::to_string(examples[i].shape(0)) +
                               " vertices but the rest mesh has " + std::to_string(num_vertices));
    example_pointers.push_back(examples[i].data());
  }
  meshik::MeshView view;
  view.vertices = rest.data();
  view.num_vertices = num_vertices;
  view.triangles = triangles.data();
  view.num_triangles = static_cast<int>(triangles.shape(0));
  std::vector<int> locked_vertices(locked.data(), locked.data() + locked.shape(0));
  meshik::DecimationResult result;
  {
    nb::gil_scoped_release unlocked;
    result = decimator(view, example_pointers, locked_vertices, target_triangles, max_normal_change_degrees,
                       meshik::DistanceBound{max_distance, relax_factor, max_relaxations});
  }
  const size_t kept = result.kept_vertices.size(), faces = result.triangles.size() / 3;
  return nb::make_tuple(to_numpy(std::move(result.kept_vertices), kept, 0),
                        to_numpy(std::move(result.triangles), faces, 3),
                        to_numpy(std::move(result.vertex_map), static_cast<size_t>(num_vertices), 0),
                        result.worst_distance, result.bound, result.relaxations);
}

// decimate(rest, triangles, examples, locked, target_triangles, max_normal_change_degrees, max_distance,
//          relax_factor, max_relaxations): the OpenMesh decimator; see run_decimator.
nb::tuple decimate(Positions rest, Triangles triangles, const std::vector<Positions>& examples, Indices locked,
                   int target_triangles, double max_normal_change_degrees, double max_distance, double relax_factor,
                   int max_relaxations) {
  return run_decimator(&meshik::decimate_example_set, rest, triangles, examples, locked, target_triangles,
                       max_normal_change_degrees, max_distance, relax_factor, max_relaxations);
}

// decimate_fast(..., threads): the same arguments and result with our own fast decimator on
// `threads` threads (0: all cores).
nb::tuple decimate_fast(Positions rest, Triangles triangles, const std::vector<Positions>& examples, Indices locked,
                        int target_triangles, double max_normal_change_degrees, double max_distance,
                        double relax_factor, int max_relaxations, int threads) {
  const auto fast = [threads](const meshik::MeshView& view, const std::vector<const double*>& poses,
                              const std::vector<int>& kept, int target, double degrees,
                              const meshik::DistanceBound& bound) {
    return meshik::decimate_example_set_fast(view, poses, kept, target, degrees, bound, threads);
  };
  return run_decimator(fast, rest, triangles, examples, locked, target_triangles, max_normal_change_degrees,
                       max_distance, relax_factor, max_relaxations);
}

}  // namespace

void bind_decimate(nb::module_& m) {
  m.def("decimate", &decimate, nb::arg("rest"), nb::arg("triangles"), nb::arg("examples"), nb::arg("locked"),
        nb::arg("target_triangles"), nb::arg("max_normal_change_degrees") = 60.0,
        nb::arg("max_distance") = std::numeric_limits<double>::infinity(), nb::arg("relax_factor") = 1.25,
        nb::arg("max_relaxations") = 10,
        "Deformation-aware decimation of an example set (OpenMesh decimater).\n\n"
        "rest: #V by 3 float64; triangles: #F by 3 int32; examples: list of #V by 3 float64;\n"
        "locked: vertex ids never removed (the handles); target_triangles: stop at this many.\n"
        "The error of a collapse is the quadric error summed over the rest pose and every example;\n"
        "collapses that flip a triangle by more than max_normal_change_degrees in any pose, or that leave a\n"
        "removed vertex farther than max_distance from the simplified surface (or a simplified triangle's\n"
        "sample point from the original surface) in any pose, are refused; short of the target, the bound\n"
        "is multiplied by relax_factor up to max_relaxations times, then lifted.\n"
        "Returns (kept_vertices #S, triangles #SF by 3 indexing kept_vertices, vertex_map #V,\n"
        "worst_distance: the largest such distance over all poses, bound: the bound at the end,\n"
        "relaxations: how many times it was relaxed).");
  m.def("decimate_fast", &decimate_fast, nb::arg("rest"), nb::arg("triangles"), nb::arg("examples"),
        nb::arg("locked"), nb::arg("target_triangles"), nb::arg("max_normal_change_degrees") = 60.0,
        nb::arg("max_distance") = std::numeric_limits<double>::infinity(), nb::arg("relax_factor") = 1.25,
        nb::arg("max_relaxations") = 10, nb::arg("threads") = 0,
        "The same decimation as decimate (same arguments, guards and result) by MeshIK's own fast\n"
        "decimator (no OpenMesh): collapses popped from a heap ordered by the summed quadric error, guards\n"
        "checked when popped. threads: 0 for all cores; the result is the same for any count.");
}
