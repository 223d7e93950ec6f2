// meshik._core: the Python face of cpp_core (ExampleSet, Solver, SolveResult, InputError,
// Cancelled). numpy arrays in and out; float32/float64 and int32/int64 inputs are converted;
// shapes are checked with messages naming the argument. The GIL is released while the core
// precomputes, factors and solves.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>

#include <climits>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "decimate_module.h"
#include "meshik/meshik.h"
#include "meshik/option_names.h"
#include "meshik/thread_limit.h"
#include "owned_array.h"

namespace nb = nanobind;
using namespace nb::literals;

namespace {

using NumpyArray = nb::ndarray<nb::numpy, double>;

// str(value) as a C++ string.
std::string text_of(const nb::handle& value) {
  return nb::cast<std::string>(value.attr("__str__")());
}

// numpy.asarray(value), and its dtype kind ('f', 'i', 'u', 'b', ...).
nb::object as_numpy(const nb::handle& value) {
  return nb::module_::import_("numpy").attr("asarray")(value);
}
char dtype_kind(const nb::object& array) {
  return nb::cast<std::string>(array.attr("dtype").attr("kind"))[0];
}

// Checks that array has `dims` dimensions with the given sizes (-1: any); raises InputError
// "<name> must have shape (n, 3), got (...)" otherwise.
void check_shape(const nb::object& array, const char* name, std::vector<long> dims,
                 const std::string& expected) {
  const nb::tuple shape = nb::cast<nb::tuple>(array.attr("shape"));
  bool ok = shape.size() == dims.size();
  for (size_t d = 0; ok && d < dims.size(); ++d)
    ok = dims[d] < 0 || nb::cast<long>(shape[d]) == dims[d];
  if (!ok)
    throw meshik::InputError(std::string(name) + " must have shape " + expected + ", got " +
                             text_of(array.attr("shape")));
}

// A real-valued array (floats or integers) converted to contiguous float64 values.
std::vector<double> float_values(const nb::object& array, const char* name) {
  const char kind = dtype_kind(array);
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw meshik::InputError(std::string(name) + " must hold real numbers, got dtype " +
                             text_of(array.attr("dtype")));
  nb::object converted = nb::module_::import_("numpy").attr("ascontiguousarray")(array, "dtype"_a = "float64");
  const auto view = nb::cast<nb::ndarray<const double, nb::c_contig, nb::device::cpu>>(converted);
  return std::vector<double>(view.data(), view.data() + view.size());
}

// An integer array converted to int values (range-checked). An empty array may have any dtype
// (numpy makes [] float64).
std::vector<int> int_values(const nb::object& array, const char* name) {
  if (nb::cast<size_t>(array.attr("size")) == 0) return {};
  const char kind = dtype_kind(array);
  if (kind != 'i' && kind != 'u')
    throw meshik::InputError(std::string(name) + " must be an integer array, got dtype " +
                             text_of(array.attr("dtype")));
  nb::object converted = nb::module_::import_("numpy").attr("ascontiguousarray")(array, "dtype"_a = "int64");
  const auto view = nb::cast<nb::ndarray<const int64_t, nb::c_contig, nb::device::cpu>>(converted);
  std::vector<int> values(view.size());
  for (size_t i = 0; i < view.size(); ++i) {
    if (view.data()[i] < INT_MIN || view.data()[i] > INT_MAX)
      throw meshik::InputError(std::string(name) + " entry " + std::to_string(i) + " (" +
                               std::to_string(view.data()[i]) + ") does not fit a 32-bit index");
    values[i] = static_cast<int>(view.data()[i]);
  }
  return values;
}

// A #rows by 3 float64 array (rows = -1: any number of rows).
std::vector<double> point_rows(const nb::handle& value, const char* name, long rows,
                               const std::string& expected) {
  const nb::object array = as_numpy(value);
  check_shape(array, name, {rows, 3}, expected);
  return float_values(array, name);
}

// A numpy array that owns `values` (moved), with the given shape.
NumpyArray to_numpy(std::vector<double>&& values, std::initializer_list<size_t> shape) {
  return meshik_bindings::owned_array(std::move(values), shape);
}

// A 1-D int64 numpy array holding a copy of indices.
nb::object index_array(const std::vector<int>& indices) {
  auto* owned = new std::vector<int64_t>(indices.begin(), indices.end());
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<int64_t>*>(p); });
  const size_t shape[1] = {owned->size()};
  return nb::cast(nb::ndarray<nb::numpy, int64_t>(owned->data(), 1, shape, owner));
}

// "nonlinear" or "linear" as a FeatureSpace; InputError otherwise.
meshik::FeatureSpace parse_feature_space(const std::string& name) {
  if (const auto feature_space = meshik::feature_space_from_name(name)) return *feature_space;
  throw meshik::InputError("feature_space must be 'nonlinear' or 'linear', got '" + name + "'");
}

// "affine" or "free" as a Blend; InputError otherwise.
meshik::Blend parse_blend(const std::string& name) {
  if (const auto blend = meshik::blend_from_name(name)) return *blend;
  throw meshik::InputError("blend must be 'affine' or 'free', got '" + name + "'");
}

// regions: a count (int >= 1), "auto", or a (n,) integer array of vertex groups (-1: none), into
// options (regions or vertex_regions); InputError otherwise.
void parse_regions(const nb::object& regions, meshik::SolverOptions& options) {
  if (nb::isinstance<nb::str>(regions)) {
    const std::string name = nb::cast<std::string>(regions);
    if (name != "auto") throw meshik::InputError("regions must be a count, 'auto' or vertex groups, got '" + name + "'");
    options.regions = meshik::kAutomaticRegions;
  } else if (nb::isinstance<nb::int_>(regions)) {
    options.regions = nb::cast<int>(regions);
  } else {
    const nb::object array = as_numpy(regions);
    check_shape(array, "regions", {-1}, "(n,) vertex groups");
    options.vertex_regions = int_values(array, "regions");
  }
}

// "single" or "double" as a FeaturePrecision; InputError otherwise.
meshik::FeaturePrecision parse_feature_precision(const std::string& name) {
  if (name == "single") return meshik::FeaturePrecision::kSingle;
  if (name == "double") return meshik::FeaturePrecision::kDouble;
  throw meshik::InputError("feature_precision must be 'single' or 'double', got '" + name + "'");
}

// Adapts an optional Python callable progress(fraction, stage) -> bool | None to the core's
// callback, and lets Ctrl+C stop a core call: at every progress point the callback also runs
// Python's pending signal handlers, so SIGINT raises KeyboardInterrupt within one iteration.
// Returning False cancels; an exception raised by the callable or a signal handler cancels the
// core call and is re-raised by run() once the core has returned.
class PythonProgress {
 public:
  explicit PythonProgress(nb::object callable) : callable_(std::move(callable)) {}
  meshik::ProgressCallback callback() {
    return [this](double fraction, const std::string& stage) {
      nb::gil_scoped_acquire gil;
      try {
        if (PyErr_CheckSignals() != 0) throw nb::python_error();
        if (callable_.is_none()) return true;
        const nb::object answer = callable_(fraction, stage);
        return answer.is_none() || PyObject_IsTrue(answer.ptr()) == 1;
      } catch (nb::python_error&) {
        error_ = std::current_exception();
        return false;
      }
    };
  }
  // Runs core_call (GIL released); re-raises the callable's own exception if it raised one.
  template <typename F>
  auto run(F&& core_call) {
    try {
      nb::gil_scoped_release release;
      return core_call(callback());
    } catch (const meshik::Cancelled&) {
      if (error_) std::rethrow_exception(error_);
      throw;
    }
  }

 private:
  nb::object callable_;
  std::exception_ptr error_;
};

// The Python objects: an ExampleSet shared with the solvers made from it, a solve's results as
// numpy arrays, and a solver with the example set it keeps alive.
struct PyExampleSet {
  std::shared_ptr<const meshik::ExampleSet> core;
};

struct PySolveResult {
  nb::object vertices;  // numpy arrays, created once
  nb::object weights;
  nb::object energies;
  int iterations;
  double residual;
  bool converged;
  nb::object inverted_triangles;
};

struct PySolver {
  std::shared_ptr<const meshik::ExampleSet> examples;
  std::unique_ptr<meshik::Solver> solver;
};

// ExampleSet from rest_vertices (n, 3), faces (m, 3) and examples ((k, n, 3) or k arrays (n, 3)),
// with the GIL released while the core validates and precomputes.
// threads: None (all cores) or a count from 1 to kMaxThreads, as the core's ExampleSet takes it
// (0 = all cores). feature_precision: "single" or "double" (parse_feature_precision).
// Anything else (a float, a bool, an integer beyond 64 bits, a string) is an InputError naming it.
int thread_option(const nb::object& threads) {
  if (threads.is_none()) return 0;
  const std::string expected = "threads must be None (all cores) or an integer from 1 to " + std::to_string(meshik::kMaxThreads);
  if (!PyLong_Check(threads.ptr()) || PyBool_Check(threads.ptr()))
    throw meshik::InputError(expected + ", got " + nb::cast<std::string>(nb::repr(threads)));
  int overflow = 0;
  const long long count = PyLong_AsLongLongAndOverflow(threads.ptr(), &overflow);
  if (overflow != 0 || count < 1 || count > meshik::kMaxThreads)
    throw meshik::InputError(expected + ", got " + nb::cast<std::string>(nb::repr(threads)));
  return static_cast<int>(count);
}

PyExampleSet make_example_set(const nb::object& rest_vertices, const nb::object& faces,
                              const nb::object& examples, const nb::object& progress, const nb::object& threads,
                              const std::string& feature_precision) {
  const int thread_count = thread_option(threads);
  const meshik::FeaturePrecision precision = parse_feature_precision(feature_precision);
  std::vector<double> rest = point_rows(rest_vertices, "rest_vertices", -1, "(n, 3)");
  const long n = static_cast<long>(rest.size() / 3);
  const nb::object face_array = as_numpy(faces);
  check_shape(face_array, "faces", {-1, 3}, "(m, 3)");
  const std::vector<int> triangles = int_values(face_array, "faces");

  // examples: a (k, n, 3) array or a sequence of (n, 3) arrays.
  std::vector<std::vector<double>> poses;
  const std::string each = "(" + std::to_string(n) + ", 3)";
  if (nb::hasattr(examples, "ndim") && nb::cast<int>(examples.attr("ndim")) == 3) {
    const nb::object array = as_numpy(examples);
    check_shape(array, "examples", {-1, n, 3}, "(k, " + std::to_string(n) + ", 3)");
    std::vector<double> all = float_values(array, "examples");
    for (size_t start = 0; start < all.size(); start += 3 * n)
      poses.emplace_back(all.begin() + start, all.begin() + start + 3 * n);
  } else {
    size_t i = 0;
    for (nb::handle pose : examples) {
      const std::string name = "examples[" + std::to_string(i++) + "]";
      poses.push_back(point_rows(pose, name.c_str(), n, each));
    }
  }
  meshik::MeshView view{rest.data(), static_cast<int>(n), triangles.data(),
                        static_cast<int>(triangles.size() / 3)};
  std::vector<const double*> pointers;
  for (const auto& pose : poses) pointers.push_back(pose.data());
  PythonProgress python_progress(progress);
  return PyExampleSet{python_progress.run([&](const meshik::ProgressCallback& callback) {
    return std::make_shared<const meshik::ExampleSet>(view, pointers, callback, thread_count, precision);
  })};
}

// Solver over `set` for handles (h,) with the given options (GIL released while factoring);
// threads: None (all cores) or a count, for each solve (thread_option); handle_stiffness: 0 for
// hard handles, > 0 for soft ones (SolverOptions::handle_stiffness).
PySolver make_solver(std::shared_ptr<const meshik::ExampleSet> set, const nb::object& handles,
                     const std::string& feature_space, double weight_regularization,
                     int max_iterations, double tolerance, const nb::object& progress,
                     const nb::object& threads, const std::string& blend, const nb::object& regions,
                     double region_smoothness, double handle_stiffness) {
  const nb::object handle_array = as_numpy(handles);
  check_shape(handle_array, "handles", {-1}, "(h,)");
  const std::vector<int> handle_values = int_values(handle_array, "handles");
  meshik::SolverOptions options;
  options.feature_space = parse_feature_space(feature_space);
  options.weight_regularization = weight_regularization;
  options.max_iterations = max_iterations;
  options.tolerance = tolerance;
  options.threads = thread_option(threads);
  options.blend = parse_blend(blend);
  parse_regions(regions, options);
  options.region_smoothness = region_smoothness;
  options.handle_stiffness = handle_stiffness;
  PythonProgress python_progress(progress);
  auto solver = python_progress.run([&](const meshik::ProgressCallback& callback) {
    return std::make_unique<meshik::Solver>(set, handle_values, options, callback);
  });
  return PySolver{std::move(set), std::move(solver)};
}

// weights (#E,) as float64 values, shape-checked.
std::vector<double> weight_values(const nb::handle& value, const char* name, int k) {
  const nb::object array = as_numpy(value);
  check_shape(array, name, {k}, "(" + std::to_string(k) + ",)");
  std::vector<double> weights = float_values(array, name);
  for (size_t i = 0; i < weights.size(); ++i)
    if (!std::isfinite(weights[i]))
      throw meshik::InputError(std::string(name) + "[" + std::to_string(i) + "] (the weight of example " +
                               std::to_string(i) + ") is " + text_of(array[nb::int_(i)]) + ", not a finite number");
  return weights;
}

// set.blend(weights (k,)) as an (n, 3) array.
NumpyArray blend(const meshik::ExampleSet& set, const nb::object& weights,
                 meshik::FeatureSpace space, meshik::Blend how = meshik::Blend::kAffine) {
  const std::vector<double> w = weight_values(weights, "weights", set.num_examples());
  std::vector<double> pose;
  {
    nb::gil_scoped_release release;
    pose = set.blend(w.data(), space, how);
  }
  return to_numpy(std::move(pose), {static_cast<size_t>(set.num_vertices()), 3});
}

// self.solve(targets (h, 3), initial_weights (k,) or None) with the GIL released.
PySolveResult solve(const PySolver& self, const nb::object& targets,
                    const nb::object& initial_weights, const nb::object& progress) {
  const meshik::Solver& solver = *self.solver;
  const long h = static_cast<long>(solver.handles().size());
  const std::vector<double> target_values = point_rows(
      targets, "targets", h, "(" + std::to_string(h) + ", 3) (one row per handle)");
  std::vector<double> start;
  if (!initial_weights.is_none())
    start = weight_values(initial_weights, "initial_weights", solver.num_weights());
  PythonProgress python_progress(progress);
  meshik::SolveResult result = python_progress.run([&](const meshik::ProgressCallback& callback) {
    return solver.solve(target_values.data(), start.empty() ? nullptr : start.data(), callback);
  });
  const size_t n = result.vertices.size() / 3, k = result.weights.size(),
               e = result.energies.size();
  return PySolveResult{nb::cast(to_numpy(std::move(result.vertices), {n, 3})),
                       nb::cast(to_numpy(std::move(result.weights), {k})),
                       nb::cast(to_numpy(std::move(result.energies), {e})), result.iterations,
                       result.residual, result.converged, index_array(result.inverted_triangles)};
}

}  // namespace

NB_MODULE(_core, m) {
  m.doc() = "MeshIK core: pose a mesh from handles within the space of example poses.";
  nb::exception<meshik::InputError>(m, "InputError", PyExc_ValueError);
  nb::exception<meshik::Cancelled>(m, "Cancelled", PyExc_RuntimeError);
  m.attr("MAX_THREADS") = meshik::kMaxThreads;
  bind_decimate(m);

  nb::class_<PyExampleSet>(m, "ExampleSet",
                           "A rest mesh and example poses (same vertices and faces), validated, "
                           "with their per-triangle features precomputed.")
      .def("__init__",
           [](PyExampleSet* self, const nb::object& rest_vertices, const nb::object& faces,
              const nb::object& examples, const nb::object& progress, const nb::object& threads,
              const std::string& feature_precision) {
             new (self) PyExampleSet(
                 make_example_set(rest_vertices, faces, examples, progress, threads, feature_precision));
           },
           "rest_vertices"_a, "faces"_a, "examples"_a, "progress"_a = nb::none(), "threads"_a = nb::none(),
           "feature_precision"_a = "single",
           "rest_vertices: (n, 3); faces: (m, 3) integer; examples: (k, n, 3) or a sequence of "
           "(n, 3) arrays; progress: optional callable(fraction, stage) returning False to cancel; "
           "threads: None for all cores or a count (the features are the same bits for any count); "
           "feature_precision: 'single' (60 bytes per triangle and example; every blend, energy and "
           "pose still computed in double) or 'double' (120 bytes).")
      .def("blend",
           [](const PyExampleSet& self, const nb::object& weights, const std::string& space,
              const std::string& how) { return blend(*self.core, weights, parse_feature_space(space), parse_blend(how)); },
           "weights"_a, "feature_space"_a = "nonlinear", "blend"_a = "affine",
           "The examples combined with weights (k,), no handles: (n, 3) positions.")
      .def_prop_ro("num_vertices", [](const PyExampleSet& s) { return s.core->num_vertices(); })
      .def_prop_ro("num_triangles", [](const PyExampleSet& s) { return s.core->num_triangles(); })
      .def_prop_ro("num_examples", [](const PyExampleSet& s) { return s.core->num_examples(); })
      .def_prop_ro("feature_precision", [](const PyExampleSet& s) {
        return s.core->feature_precision() == meshik::FeaturePrecision::kSingle ? "single" : "double";
      });

  nb::class_<PySolveResult>(m, "SolveResult", "The pose found by Solver.solve().")
      .def_ro("vertices", &PySolveResult::vertices, "(n, 3) float64 posed positions")
      .def_ro("weights", &PySolveResult::weights, "(k,) blend weights")
      .def_ro("energies", &PySolveResult::energies,
              "energy at the start and after each accepted iteration")
      .def_ro("iterations", &PySolveResult::iterations, "Gauss-Newton iterations taken")
      .def_ro("residual", &PySolveResult::residual, "final energy")
      .def_ro("converged", &PySolveResult::converged, "stopped by the tolerance")
      .def_ro("inverted_triangles", &PySolveResult::inverted_triangles,
              "(t,) int64 ascending indices of the faces that the pose turns over against the "
              "orientation their blended deformation asks for (folds, e.g. beside a handle dragged "
              "where the examples cannot follow)")
      .def("__repr__", [](const PySolveResult& r) {
        return "SolveResult(iterations=" + std::to_string(r.iterations) +
               ", residual=" + std::to_string(r.residual) +
               ", converged=" + (r.converged ? "True" : "False") + ")";
      });

  nb::class_<PySolver>(m, "Solver",
                       "Poses the mesh from target positions of a fixed set of handle vertices; "
                       "the handle set's system is factored once at construction.")
      .def("__init__",
           [](PySolver* self, const nb::object& rest_vertices, const nb::object& faces,
              const nb::object& examples, const nb::object& handles,
              const std::string& feature_space, double weight_regularization, int max_iterations,
              double tolerance, const nb::object& progress, const nb::object& threads,
              const std::string& feature_precision, const std::string& blend, const nb::object& regions,
              double region_smoothness, double handle_stiffness) {
             PyExampleSet set =
                 make_example_set(rest_vertices, faces, examples, progress, threads, feature_precision);
             new (self) PySolver(make_solver(std::move(set.core), handles, feature_space,
                                             weight_regularization, max_iterations, tolerance,
                                             progress, threads, blend, regions, region_smoothness,
                                             handle_stiffness));
           },
           "rest_vertices"_a, "faces"_a, "examples"_a, "handles"_a,
           "feature_space"_a = "nonlinear", "weight_regularization"_a = 0.0,
           "max_iterations"_a = 30, "tolerance"_a = 1e-10, "progress"_a = nb::none(),
           "threads"_a = nb::none(), "feature_precision"_a = "single", "blend"_a = "affine",
           "regions"_a = 1, "region_smoothness"_a = 0.01, "handle_stiffness"_a = 0.0,
           "blend: 'affine' (stretches tied to the rest, default) or 'free' (the paper's "
           "w_0 I + sum_i w_i S_i, the rest pose as example 0: k + 1 weights, the rest's first); regions: 1 (one weight vector), a count of regions clustered from the "
           "examples, 'auto', or (n,) vertex groups (-1: none); the weights are then (regions, k) "
           "flattened region-major; region_smoothness: pull between neighbouring regions' weights; "
           "handle_stiffness: 0 (hard handles, each exactly at its target) or > 0 (soft: each handle "
           "pulled towards its target with that stiffness, relative to how its triangles hold it).")
      .def_static(
          "from_example_set",
          [](const PyExampleSet& set, const nb::object& handles, const std::string& feature_space,
             double weight_regularization, int max_iterations, double tolerance,
             const nb::object& progress, const nb::object& threads, const std::string& blend,
             const nb::object& regions, double region_smoothness, double handle_stiffness) {
            return make_solver(set.core, handles, feature_space, weight_regularization, max_iterations, tolerance,
                               progress, threads, blend, regions, region_smoothness, handle_stiffness);
          },
          "example_set"_a, "handles"_a, "feature_space"_a = "nonlinear",
          "weight_regularization"_a = 0.0, "max_iterations"_a = 30, "tolerance"_a = 1e-10,
          "progress"_a = nb::none(), "threads"_a = nb::none(), "blend"_a = "affine", "regions"_a = 1,
          "region_smoothness"_a = 0.01, "handle_stiffness"_a = 0.0,
          "A solver sharing example_set's precomputed features. threads: of each solve (None: all "
          "cores; the pose is the same bits for any count).")
      .def("solve", &solve, "targets"_a, "initial_weights"_a = nb::none(),
           "progress"_a = nb::none(),
           "targets: (h, 3) positions of the handles in order; initial_weights: (num_weights,) warm start "
           "(default: the rest pose, w = 0).")
      .def("blend",
           [](const PySolver& self, const nb::object& weights) {
             return blend(*self.examples, weights, self.solver->options().feature_space,
                          self.solver->options().blend);
           },
           "weights"_a, "The examples combined with weights (k,) in this solver's feature space.")
      .def_prop_ro("handles", [](const PySolver& self) { return index_array(self.solver->handles()); })
      .def_prop_ro("num_examples", [](const PySolver& s) { return s.examples->num_examples(); })
      .def_prop_ro("num_regions", [](const PySolver& s) { return s.solver->num_regions(); })
      .def_prop_ro("num_weights", [](const PySolver& s) { return s.solver->num_weights(); })
      .def_prop_ro("blend_mode", [](const PySolver& s) {
        return std::string(meshik::blend_name(s.solver->options().blend));
      })
      .def_prop_ro("triangle_regions", [](const PySolver& s) { return index_array(s.solver->triangle_regions()); },
                   "(m,) int64: the region with the largest share of each face")
      .def_prop_ro("num_vertices", [](const PySolver& s) { return s.examples->num_vertices(); })
      .def_prop_ro("feature_space",
                   [](const PySolver& s) {
                     return std::string(s.solver->options().feature_space ==
                                                meshik::FeatureSpace::kLinear
                                            ? "linear"
                                            : "nonlinear");
                   })
      .def_prop_ro("example_set", [](const PySolver& s) { return PyExampleSet{s.examples}; });
}
