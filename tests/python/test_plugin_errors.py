"""Bad input to the MeshIK filters raises pymeshlab.PyMeshLabException with a message that says
what and where; the host process survives and the MeshSet keeps working."""
import json

import numpy as np
import pymeshlab
import pytest

from pipeline_meshes import grid
from plugin_helpers import BLEND, POSE, apply_refused, mesh_set, select_vertices

GRID = (5, 4.0)  # 5 by 5 vertices at integer coordinates: vertex 24 is (4, 4, 0)
SMALL_GRID = (3, 2.0)


def bent(vertices: np.ndarray, amount: float) -> np.ndarray:
    """The grid bent along x (an example pose)."""
    posed = vertices.copy()
    posed[:, 2] = amount * vertices[:, 0] ** 2
    return posed


@pytest.fixture
def grid_set():
    """A MeshSet: a 5x5 grid as the rest layer, two bent examples, vertices 0 and 24 selected."""
    vertices, faces = grid(*GRID)
    ms = mesh_set(vertices, faces, [bent(vertices, 0.1), bent(vertices, -0.2)])
    select_vertices(ms, [0, 24])
    return ms


def raises(ms, filter_name, *fragments, **parameters):
    """Applies the filter expecting a PyMeshLabException whose message holds every fragment."""
    message = apply_refused(ms, filter_name, **parameters)
    for fragment in fragments:
        assert fragment in message, message
    return message


def still_works(ms):
    """The MeshSet still runs the filter after an error."""
    ms.set_current_mesh(0)
    select_vertices(ms, [0, 24])
    output = ms.apply_filter(POSE, targetsource="Handle transform")
    assert output["layer_id"] > 0


def test_no_vertex_selected(grid_set):
    grid_set.set_selection_none()
    raises(grid_set, POSE, "no vertex is selected", '"rest"', targetsource="Handle transform")
    raises(grid_set, POSE, "no vertex is selected", targetsource="Target layer", targetmesh=1)
    still_works(grid_set)


def test_no_example_layer():
    vertices, faces = grid(*GRID)
    ms = mesh_set(vertices, faces, [])
    select_vertices(ms, [0])
    raises(ms, POSE, "no example layer", "25 vertices and 32 triangles", targetsource="Handle transform")
    raises(ms, BLEND, "no example layer")


def test_example_with_other_triangles_is_named():
    vertices, faces = grid(*GRID)
    other = faces.copy()
    other[7] = other[7][[0, 2, 1]]  # the same counts, one triangle flipped
    ms = mesh_set(vertices, faces, [bent(vertices, 0.1)], labels=["good"])
    ms.add_mesh(pymeshlab.Mesh(bent(vertices, 0.2), other), "flipped")
    ms.set_current_mesh(0)
    select_vertices(ms, [0, 24])
    raises(ms, POSE, '"flipped"', "other triangles", "triangle 7", targetsource="Handle transform")
    raises(ms, BLEND, '"flipped"', "triangle 7", weights="1, 0")


def test_named_example_with_other_vertex_count_is_named(grid_set):
    small_vertices, small_faces = grid(*SMALL_GRID)
    grid_set.add_mesh(pymeshlab.Mesh(small_vertices, small_faces), "small")
    grid_set.set_current_mesh(0)
    raises(grid_set, POSE, '"small"', "9 vertices", "25", examplelayers="1, small",
           targetsource="Handle transform")
    raises(grid_set, POSE, 'no layer with id or name "nothing"', examplelayers="nothing",
           targetsource="Handle transform")
    raises(grid_set, POSE, "is the rest layer", examplelayers="0, 1", targetsource="Handle transform")
    still_works(grid_set)


def test_degenerate_rest_triangle():
    vertices, faces = grid(*GRID)
    collapsed = vertices.copy()
    collapsed[6] = collapsed[0]  # triangles 0 (0, 1, 6) and 1 (0, 6, 5) lose their area
    ms = mesh_set(collapsed, faces, [bent(vertices, 0.1)])
    select_vertices(ms, [0, 24])
    message = raises(ms, POSE, "zero area", 'the rest mesh is layer "rest" (layer 0)', targetsource="Handle transform")
    assert "triangle 0 " in message or "triangle 1 " in message, message


def test_non_finite_example_names_its_layer():
    vertices, faces = grid(*GRID)
    broken = bent(vertices, 0.2)
    broken[3, 1] = np.nan
    ms = mesh_set(vertices, faces, [bent(vertices, 0.1), broken], labels=["fine", "broken"])
    select_vertices(ms, [0, 24])
    raises(ms, POSE, "vertex 3", "non-finite", 'example 1 is layer "broken" (layer 2)', targetsource="Handle transform")
    raises(ms, BLEND, 'example 1 is layer "broken" (layer 2)', weights="0, 1")


def test_target_layer_with_other_vertex_count(grid_set):
    small_vertices, small_faces = grid(*SMALL_GRID)
    grid_set.add_mesh(pymeshlab.Mesh(small_vertices, small_faces), "small")
    grid_set.set_current_mesh(0)
    raises(grid_set, POSE, "targetmesh", '"small"', "9 vertices", targetsource="Target layer", targetmesh=3)
    raises(grid_set, POSE, "targetmesh: there is no layer 17", targetsource="Target layer", targetmesh=17)


def test_non_affine_handle_transform(grid_set):
    matrix = np.eye(4)
    matrix[3, 0] = 0.5
    raises(grid_set, POSE, "handletransform", "0 0 0 1", targetsource="Handle transform", handletransform=matrix)


def test_bad_weights(grid_set):
    raises(grid_set, BLEND, "weights: expected 2 numbers", "got 3", weights="1, 0, 0")
    raises(grid_set, BLEND, 'weights: "x" is not a number', weights="1, x")


def write_constraints(tmp_path, document, name="shot.json"):
    """Writes a constraint document (a dict, or raw text) and returns its path."""
    path = tmp_path / name
    path.write_text(document if isinstance(document, str) else json.dumps(document))
    return path


def constraint_document(**changes):
    """A valid constraint document for the grid: corner handles, two frames; `changes` replace members."""
    document = {
        "format": "meshik-constraints", "version": 1, "rest": "rest.obj", "examples": ["a.obj", "b.obj"],
        "handles": {"left": [0, 5], "right": {"near": [4.0, 4.0, 0.0], "radius": 0.1}},
        "frames": [{"name": "up", "targets": {"left": [[0, 0, 0.1], [0, 1, 0.1]]}},
                   {"targets": {"right": {"translate": [0, 0, 0.3]}}}],
    }
    document.update(changes)
    return document


def one_frame(targets):
    """A constraint document for the grid whose only frame has these targets."""
    return constraint_document(frames=[{"targets": targets}])


SCALING = [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
BAD_CONSTRAINT_FILES = [
    ("{\n  not json", ["not valid JSON: line 2 column"]),
    (constraint_document(format="other"), ['format: expected "meshik-constraints"']),
    (constraint_document(version=2), ["version: version 2 is not supported"]),
    (constraint_document(handles={"left": [0, 99], "right": [24]}),
     ["handles.left[1]: vertex 99 is out of range", "25 vertices"]),
    (constraint_document(handles={"left": [0, 0], "right": [24]}),
     ["handles.left[1]: vertex 0 is already a handle"]),
    (constraint_document(handles={"left": [0, 5], "right": {"near": [9, 9, 9], "radius": 0.5}}),
     ["handles.right: no rest vertex within radius 0.5"]),
    (one_frame({"left": [[0, 0, 0], [0, 1]]}), ["frames[0].targets.left[1]: expected 3 numbers, got a list of 2"]),
    (one_frame({"left": [[0, 0, 0]]}),
     ["frames[0].targets.left: expected 2 positions (one per handle vertex), got 1"]),
    (one_frame({"knee": {"translate": [0, 0, 1]}}), ['frames[0].targets.knee: no handle group named "knee"']),
    (one_frame({"left": {"rotate": {"axis": [0, 0, 0], "degrees": 5}}}),
     ["frames[0].targets.left.rotate.axis: the rotation axis must have a non-zero"]),
    (one_frame({"left": {"matrix": SCALING}}), ["frames[0].targets.left.matrix: not a rigid motion"]),
    (one_frame({"left": {"scale": 2}}), ["frames[0].targets.left.scale: unknown member"]),
    (constraint_document(frames=[]), ["frames: expected a non-empty list"]),
]


@pytest.mark.parametrize("document, fragments", BAD_CONSTRAINT_FILES)
def test_bad_constraint_file_names_the_json_path(grid_set, tmp_path, document, fragments):
    path = write_constraints(tmp_path, document)
    message = raises(grid_set, POSE, str(path), *fragments, targetsource="Constraint file",
                     constraintfile=str(path))
    assert "Details" in message  # pymeshlab's wrapping of the filter's own message
    still_works(grid_set)


def test_constraint_file_frame_and_selection_errors(grid_set, tmp_path):
    path = write_constraints(tmp_path, constraint_document())
    raises(grid_set, POSE, 'no frame named or numbered "7"', "2 frames", targetsource="Constraint file",
           constraintfile=str(path), frame="7")
    select_vertices(grid_set, [0, 12])
    raises(grid_set, POSE, "vertex 12 is selected", "no handle in", targetsource="Constraint file",
           constraintfile=str(path), frame="up")
    missing = tmp_path / "missing.json"
    raises(grid_set, POSE, f"{missing}: constraint file not found", targetsource="Constraint file",
           constraintfile=str(missing))
    raises(grid_set, POSE, "constraintfile: no constraint file given", targetsource="Constraint file")


def test_constraint_file_carries_targets_forward(grid_set, tmp_path):
    # Frame 1 moves only "right": "left" keeps frame 0's targets; selecting a subset of the
    # file's handles poses with those only.
    path = write_constraints(tmp_path, constraint_document())
    grid_set.set_selection_none()
    both = grid_set.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame="1")
    posed = grid_set.mesh(both["layer_id"]).vertex_matrix()
    np.testing.assert_allclose(posed[[0, 5, 24]], [[0, 0, 0.1], [0, 1, 0.1], [4, 4, 0.3]], atol=1e-6)
    select_vertices(grid_set, [0, 5])
    left = grid_set.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame="up")
    posed = grid_set.mesh(left["layer_id"]).vertex_matrix()
    np.testing.assert_allclose(posed[[0, 5]], [[0, 0, 0.1], [0, 1, 0.1]], atol=1e-6)


def test_a_pose_or_blend_beyond_double_precision_writes_no_layer(grid_set):
    """Issue 12, defect 3: huge targets or weights are an error, never a NaN layer."""
    layers = grid_set.mesh_number()
    matrix = np.eye(4)
    matrix[0, 3] = 1e300
    matrix[1, 1] = matrix[2, 2] = 1.0
    select_vertices(grid_set, [0, 24])
    raises(grid_set, POSE, "finite range", targetsource="Handle transform", handletransform=matrix)
    raises(grid_set, BLEND, "finite range", weights="1e308, 1e308")
    assert grid_set.mesh_number() == layers
    still_works(grid_set)


def test_a_component_without_a_handle_is_refused_like_the_cli():
    """Issue 12, defect 9: two separate triangles, a handle on one only."""
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 0, 0], [6, 0, 0], [5, 1, 0]], dtype=float)
    faces = np.array([[0, 1, 2], [3, 4, 5]])
    example = vertices + np.array([0.0, 0.0, 0.1]) * np.arange(6)[:, None]
    ms = mesh_set(vertices, faces, [example])
    select_vertices(ms, [0])
    raises(ms, POSE, "connected component containing vertex 3", "has no handle", targetsource="Handle transform")
