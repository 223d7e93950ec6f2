// meshik._constraints: the Python face of the constraint-file library (cpp_core/constraints).
// meshik/constraints.py wraps it into the pipeline's dataclasses. Errors are raised as
// meshik.errors.ConstraintError with the library's message (file, JSON path, problem).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "meshik/constraints/constraint_file.h"
#include "owned_array.h"

namespace nb = nanobind;
using namespace nb::literals;
namespace mc = meshik::constraints;

namespace {

using RestArray = nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
using TargetArray = nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
using IndexArray = nb::ndarray<const std::int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

// A numpy array of the given shape that owns `values` (moved to the heap).
template <typename T>
nb::object owning_array(std::vector<T>&& values, std::initializer_list<size_t> shape) {
  return nb::cast(meshik_bindings::owned_array(std::move(values), shape));
}

// (group names, list of #group index arrays, #H handle array, #frames by #H by 3 targets, frame names).
nb::tuple resolve_document(const mc::ConstraintDocument& document, RestArray rest, std::int64_t last_frame) {
  mc::ResolvedConstraints resolved;
  {
    nb::gil_scoped_release release;
    resolved = mc::resolve_constraints(document, rest.data(), static_cast<std::int64_t>(rest.shape(0)), last_frame);
  }
  nb::list groups;
  for (auto& group : resolved.groups) groups.append(owning_array(std::move(group), {group.size()}));
  const size_t handle_count = resolved.handles.size(), frame_count = resolved.frame_names.size();
  return nb::make_tuple(resolved.group_names, groups, owning_array(std::move(resolved.handles), {handle_count}),
                        owning_array(std::move(resolved.targets), {frame_count, handle_count, 3}),
                        resolved.frame_names);
}

// Writes a one-frame file; groups: (name, #group int64 indices, #group by 3 float64 targets).
void write_file(const std::string& path, const std::string& rest, const std::vector<std::string>& examples,
           const std::vector<std::tuple<std::string, IndexArray, TargetArray>>& groups, const std::string& frame_name) {
  std::vector<mc::GroupPositions> content;
  for (const auto& [name, vertices, targets] : groups)
    content.push_back({name, std::vector<std::int64_t>(vertices.data(), vertices.data() + vertices.size()),
                       std::vector<double>(targets.data(), targets.data() + targets.size())});
  mc::write_constraint_file(path, rest, examples, content, frame_name);
}

}  // namespace

NB_MODULE(_constraints, m) {
  m.doc() = "The constraint-file library (cpp_core/constraints); use meshik.constraints instead.";
  nb::register_exception_translator([](const std::exception_ptr& error, void*) {
    try {
      std::rethrow_exception(error);
    } catch (const mc::ConstraintError& constraint_error) {
      nb::object type = nb::module_::import_("meshik.errors").attr("ConstraintError");
      PyErr_SetString(type.ptr(), constraint_error.what());
    }
  });

  nb::class_<mc::HandleGroup>(m, "HandleGroup")
      .def_ro("name", &mc::HandleGroup::name)
      .def_ro("vertices", &mc::HandleGroup::vertices)
      .def_ro("near", &mc::HandleGroup::near)
      .def_ro("radius", &mc::HandleGroup::radius);
  nb::class_<mc::GroupTarget>(m, "GroupTarget")
      .def_ro("group", &mc::GroupTarget::group)
      .def_ro("rigid", &mc::GroupTarget::rigid)
      .def_ro("positions", &mc::GroupTarget::positions)
      .def_ro("rotation", &mc::GroupTarget::rotation)
      .def_ro("translation", &mc::GroupTarget::translation)
      .def_ro("center", &mc::GroupTarget::center);
  nb::class_<mc::Frame>(m, "Frame").def_ro("name", &mc::Frame::name).def_ro("targets", &mc::Frame::targets);
  nb::class_<mc::RegionGroup>(m, "RegionGroup")
      .def_ro("name", &mc::RegionGroup::name)
      .def_ro("vertices", &mc::RegionGroup::vertices);
  nb::class_<mc::RegionSetting>(m, "RegionSetting")
      .def_ro("count", &mc::RegionSetting::count)
      .def_ro("automatic", &mc::RegionSetting::automatic)
      .def_ro("groups", &mc::RegionSetting::groups);
  nb::class_<mc::ConstraintDocument>(m, "ConstraintDocument")
      .def_ro("source", &mc::ConstraintDocument::source)
      .def_ro("rest", &mc::ConstraintDocument::rest)
      .def_ro("examples", &mc::ConstraintDocument::examples)
      .def_ro("examples_glob", &mc::ConstraintDocument::examples_glob)
      .def_ro("handles", &mc::ConstraintDocument::handles)
      .def_ro("frames", &mc::ConstraintDocument::frames)
      .def_ro("feature_space", &mc::ConstraintDocument::feature_space)
      .def_ro("blend", &mc::ConstraintDocument::blend)
      .def_ro("regions", &mc::ConstraintDocument::regions)
      .def_ro("region_smoothness", &mc::ConstraintDocument::region_smoothness)
      .def_ro("weight_regularization", &mc::ConstraintDocument::weight_regularization)
      .def_ro("handle_stiffness", &mc::ConstraintDocument::handle_stiffness)
      .def_ro("max_iterations", &mc::ConstraintDocument::max_iterations)
      .def_ro("tolerance", &mc::ConstraintDocument::tolerance)
      .def_ro("fps", &mc::ConstraintDocument::fps);

  m.def("read", &mc::read_constraint_file, "path"_a, "Reads and checks a constraint file -> ConstraintDocument.");
  m.def("parse", [](nb::bytes text, const std::string& source) {
          return mc::parse_constraints(std::string_view(text.c_str(), text.size()), source);
        }, "text"_a, "source"_a, "Checks constraint-file text (UTF-8 bytes) named `source` -> ConstraintDocument.");
  m.def("validate", &mc::validate_constraint_file, "path"_a, "check_mesh_files"_a = true,
        "Every problem of a constraint file as messages (an empty list: the file is good).");
  m.def("locate_mesh_files", [](const mc::ConstraintDocument& document) {
          mc::MeshFiles files = mc::locate_mesh_files(document);
          return std::make_pair(files.rest, files.examples);
        }, "document"_a, "(absolute rest path, [absolute example paths]) of a document.");
  m.def("resolve", &resolve_document, "document"_a, "rest"_a, "last_frame"_a = -1,
        "Resolves against #V by 3 float64 rest vertices -> (group names, [#group int64 indices], #H handles, "
        "#frames by #H by 3 targets, frame names).");
  m.def("find_frame", &mc::find_frame, "document"_a, "frame"_a, "0-based index of the frame named, else numbered, `frame`.");
  m.def("write", &write_file, "path"_a, "rest"_a, "examples"_a, "groups"_a, "frame_name"_a = "0001",
        "Writes a one-frame constraint file; groups: [(name, #group int64 indices, #group by 3 float64 targets)].");
}
