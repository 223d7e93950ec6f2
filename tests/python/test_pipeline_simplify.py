"""Consistent simplification of example sets by both deformation-aware decimators: MeshIK's own
fast one and OpenMesh's (the same contract: a subset of the vertices, handles locked, every pose)."""
import numpy as np
import pytest

from meshik.errors import PipelineError
from meshik.inputs.meshio import ExampleMeshes, surface_distance
from meshik import _core
from meshik.posing.simplify import SIMPLIFIERS, remap_handles, simplify
from pipeline_meshes import bend, bump, grid, tube


@pytest.fixture(scope="module")
def tube_meshes():
    """A 600-vertex tube with two bent examples (90 degrees about y and x)."""
    vertices, faces = tube(rings=30, segments=20)
    examples = (bend(vertices, 90, "y"), bend(vertices, 90, "x"))
    return ExampleMeshes(rest=vertices, faces=faces, examples=examples, rest_path="rest", example_paths=("a", "b"))


def poses(meshes):
    """The rest pose followed by every example."""
    return (meshes.rest,) + tuple(meshes.examples)


HANDLES = np.array([0, 5, 10, 590, 595])


@pytest.mark.parametrize("method", ["fast", "openmesh"])
def test_every_pose_shares_the_simplified_triangles(tube_meshes, method):
    result = simplify(tube_meshes, 300, HANDLES, method)
    simplified = result.meshes
    assert len(simplified.faces) <= 300 and len(simplified.examples) == 2
    count = len(simplified.rest)
    assert simplified.faces.min() == 0 and simplified.faces.max() == count - 1
    assert len(np.unique(simplified.faces)) == count  # every vertex is used
    assert result.vertex_map.shape == (600,) and set(result.vertex_map) == set(range(count))
    np.testing.assert_array_equal(result.vertex_map[result.source_vertex], np.arange(count))
    for pose, original in zip(poses(simplified), poses(tube_meshes)):
        assert pose.shape == (count, 3)
        corners = pose[simplified.faces]
        areas = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
        assert areas.min() > 0
        # the handles stay where they are, in every pose
        np.testing.assert_array_equal(pose[result.vertex_map[HANDLES]], original[HANDLES])


def test_fast_gives_the_same_result_on_any_thread_count(tube_meshes):
    one, two = (simplify(tube_meshes, 150, HANDLES, "fast", threads=threads) for threads in (1, 2))
    np.testing.assert_array_equal(one.meshes.faces, two.meshes.faces)
    np.testing.assert_array_equal(one.vertex_map, two.vertex_map)
    assert one.distance_bound == two.distance_bound and one.relaxations == two.relaxations


@pytest.mark.parametrize("method", SIMPLIFIERS)
def test_keeps_handles_and_original_positions(tube_meshes, method):
    ring = np.arange(580, 600)  # the whole top ring, simplified hard
    result = simplify(tube_meshes, 60, ring, method)
    assert len(result.meshes.faces) <= 60
    assert set(ring) <= set(result.source_vertex)
    handles, kept = remap_handles(result, ring)
    assert len(handles) == len(ring)  # locked: none merged
    np.testing.assert_array_equal(result.source_vertex[handles], ring[kept])
    for pose, original in zip(poses(result.meshes), poses(tube_meshes)):
        np.testing.assert_array_equal(pose, original[result.source_vertex])
    unchanged, order = remap_handles(None, ring)
    np.testing.assert_array_equal(unchanged, ring) and np.testing.assert_array_equal(order, np.arange(20))


@pytest.mark.parametrize("method, decimate", [("fast", _core.decimate_fast), ("openmesh", _core.decimate)])
def test_keeps_detail_that_moves_in_an_example(method, decimate):
    """A flat grid whose example raises a bump: the rest pose alone says 'flat, remove anything';
    summed over the poses, the error keeps the bump's vertices."""
    vertices, faces = grid(size=24)
    raised = bump(vertices, center=(0.3, 0.6), height=0.3, width=0.08)
    with_example = ExampleMeshes(rest=vertices, faces=faces, examples=(raised,), rest_path="r", example_paths=("e",))
    aware = simplify(with_example, 200, np.array([0]), method)
    # the same collapses chosen from the rest pose alone, then applied to the example
    kept, rest_faces, *_ = decimate(vertices, faces.astype(np.int32), [], np.array([0], np.int32), 200)
    rest_only_error = surface_distance(raised[kept], rest_faces, raised, faces)
    aware_error = surface_distance(aware.meshes.examples[0], aware.meshes.faces, raised, faces)
    assert aware_error < 0.25 * rest_only_error


def test_openmesh_names_the_non_manifold_triangle():
    vertices, faces = grid(size=5)
    faces = np.concatenate([faces, faces[:1]])  # a triangle twice: its edges have three triangles
    meshes = ExampleMeshes(rest=vertices, faces=faces, examples=(vertices,), rest_path="grid.obj", example_paths=("e",))
    with pytest.raises(PipelineError, match=r"^grid.obj: triangle 32 and triangle 0 both run along the edge"):
        simplify(meshes, 10, np.array([0]), "openmesh")


def test_fast_keeps_the_non_manifold_parts():
    """Two grids touching at one corner vertex (its triangles form two fans), one triangle listed
    twice: fast simplifies the rest and keeps those vertices; every pose stays on its own vertices."""
    vertices, faces = grid(size=5)
    shifted = vertices + np.array([-1.0, -1.0, 0.5])
    corner = int(np.argmin(vertices.sum(axis=1)))  # the first grid's corner (0, 0) ...
    far = int(np.argmax(shifted.sum(axis=1)))      # ... is the second grid's far corner
    second = np.where(faces == far, corner, faces + len(vertices))
    both = np.concatenate([vertices, shifted])
    all_faces = np.concatenate([faces, second, faces[5:6]])
    raised = both + np.array([0.0, 0.0, 0.1]) * both[:, :1]
    meshes = ExampleMeshes(rest=both, faces=all_faces, examples=(raised,), rest_path="pair.obj", example_paths=("e",))
    result = simplify(meshes, 20, np.array([1]), "fast")
    assert len(result.meshes.faces) <= 20
    for vertex in (corner, *faces[5]):
        assert vertex in result.source_vertex
    np.testing.assert_array_equal(result.meshes.examples[0], raised[result.source_vertex])
    with pytest.raises(PipelineError, match=r"^pair.obj: "):
        simplify(meshes, 20, np.array([1]), "openmesh")


def test_bad_requests():
    vertices, faces = grid(size=5)
    meshes = ExampleMeshes(rest=vertices, faces=faces, examples=(vertices,), rest_path="r", example_paths=("e",))
    with pytest.raises(PipelineError, match="unknown simplifier 'quadric'"):
        simplify(meshes, 10, np.array([0]), "quadric")
    with pytest.raises(PipelineError, match="cannot simplify 32 triangles to 32"):
        simplify(meshes, 32, np.array([0]), "fast")
