"""Helpers for the MeshLab plugin tests: the built plugin loaded once into pymeshlab, mesh sets
with a rest layer and example layers, vertex selection, and comparisons."""
import os
import pathlib

import numpy as np
import pymeshlab
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLUGIN_DIR = pathlib.Path(os.environ.get("MESHIK_PLUGIN_DIR", ROOT / "build" / "plugin"))
POSE = "compute_coord_meshik_pose"
BLEND = "compute_coord_meshik_blend"

_loaded = []


def plugin_path(precision: str = "double") -> pathlib.Path:
    """The built plugin of a precision ("double" for pymeshlab, "float" for MeshLab releases)."""
    return PLUGIN_DIR / precision / "libfilter_meshik.so"


def load_plugin() -> None:
    """Loads the double plugin into pymeshlab (once per process); fails when it is not built."""
    if _loaded:
        return
    path = plugin_path("double")
    if not path.is_file():
        pytest.fail(f"the MeshLab plugin is not built: {path} is missing (run `make build`)")
    pymeshlab.load_plugin(str(path))
    _loaded.append(path)


def mesh_set(rest: np.ndarray, faces: np.ndarray, examples, labels=None) -> pymeshlab.MeshSet:
    """A MeshSet with the rest mesh as layer 0 (the current layer) and the examples as layers 1..#E.

    rest: #V by 3; faces: #F by 3; examples: #E arrays of #V by 3; labels: #E layer names.
    """
    load_plugin()
    ms = pymeshlab.MeshSet()
    faces = np.asarray(faces, dtype=np.int32)
    ms.add_mesh(pymeshlab.Mesh(np.asarray(rest, dtype=np.float64), faces), "rest")
    for i, example in enumerate(examples):
        label = labels[i] if labels else f"example_{i + 1}"
        ms.add_mesh(pymeshlab.Mesh(np.asarray(example, dtype=np.float64), faces), label)
    ms.set_current_mesh(0)
    return ms


def load_mesh_set(rest_path, example_paths) -> pymeshlab.MeshSet:
    """A MeshSet with the rest file as layer 0 (current) and the example files as layers 1..#E."""
    load_plugin()
    ms = pymeshlab.MeshSet()
    for path in [rest_path, *example_paths]:
        ms.load_new_mesh(str(path))
    ms.set_current_mesh(0)
    return ms


def layer_arrays(ms: pymeshlab.MeshSet, count: int):
    """(rest #V by 3, faces #F by 3, [#E examples #V by 3]) of layers 0..count-1, as pymeshlab holds them."""
    rest = ms.mesh(0)
    return (rest.vertex_matrix(), rest.face_matrix(), [ms.mesh(i).vertex_matrix() for i in range(1, count)])


def select_vertices(ms: pymeshlab.MeshSet, indices) -> None:
    """Selects exactly the given vertices of the current layer."""
    condition = " || ".join(f"(vi == {int(i)})" for i in indices)
    ms.compute_selection_by_condition_per_vertex(condselect=condition)
    selected = np.flatnonzero(ms.current_mesh().vertex_selection_array())
    assert list(selected) == sorted(int(i) for i in indices)


def apply_refused(ms: pymeshlab.MeshSet, filter_name: str, **parameters) -> str:
    """Applies a filter that must raise pymeshlab.PyMeshLabException; returns the exception's message.

    pymeshlab 2025.7 workaround (plugin/README.md, "Known issues"): a filter call that raises leaves
    pymeshlab holding a pointer into this MeshSet, which the next mesh load in any MeshSet writes
    through; once this MeshSet is freed that write corrupts the heap. A filter call that succeeds
    clears the pointer, so a read-only measuring filter runs on `ms` (it needs a current layer).
    """
    with pytest.raises(pymeshlab.PyMeshLabException) as refusal:
        ms.apply_filter(filter_name, **parameters)
    ms.get_topological_measures()
    return str(refusal.value)


def relative_error(actual: np.ndarray, expected: np.ndarray) -> float:
    """|actual - expected| / |expected| (Frobenius norms)."""
    return float(np.linalg.norm(actual - expected) / np.linalg.norm(expected))


def spread_vertices(vertices: np.ndarray, count: int) -> np.ndarray:
    """`count` ascending vertex indices spread over the mesh (farthest-point order from vertex 0)."""
    chosen = [0]
    distance = np.linalg.norm(vertices - vertices[0], axis=1)
    while len(chosen) < count:
        chosen.append(int(np.argmax(distance)))
        distance = np.minimum(distance, np.linalg.norm(vertices - vertices[chosen[-1]], axis=1))
    return np.array(sorted(chosen))
