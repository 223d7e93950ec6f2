"""Consistent simplification of example sets: fast-simplification replay with its guards, and the
deformation-aware OpenMesh decimator."""
import numpy as np
import pytest

from meshik.errors import PipelineError
from meshik.inputs.meshio import ExampleMeshes, surface_distance
from meshik.posing.simplify import remap_handles, simplify, _distance_to_own_patch, _mean_edge_length
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


def test_fast_guard_keeps_vertices_near_their_surface(tube_meshes):
    result = simplify(tube_meshes, 300, HANDLES, "fast")
    tolerance = 0.5 * _mean_edge_length(result.meshes.rest, result.meshes.faces)
    for pose, original in zip(poses(result.meshes), poses(tube_meshes)):
        distance = _distance_to_own_patch(pose, original, tube_meshes.faces, result.vertex_map)
        assert distance.max() <= tolerance
    # tolerance 0: every simplified vertex is put back on its original vertex, in every pose
    snapped = simplify(tube_meshes, 300, HANDLES, "fast", surface_tolerance=0.0)
    assert snapped.snapped == len(snapped.meshes.rest)
    for pose, original in zip(poses(snapped.meshes), poses(tube_meshes)):
        np.testing.assert_array_equal(pose, original[snapped.source_vertex])


def test_fast_aggressiveness_is_fast_simplifications_agg(tube_meshes):
    import fast_simplification

    results = {}
    for aggressiveness in (7.0, 3.0):
        result = results[aggressiveness] = simplify(tube_meshes, 150, HANDLES, "fast", aggressiveness=aggressiveness)
        _, _, collapses = fast_simplification.simplify(tube_meshes.rest, tube_meshes.faces, target_count=150,
                                                       agg=aggressiveness, return_collapses=True)
        _, faces, _ = fast_simplification.replay_simplification(tube_meshes.rest, tube_meshes.faces, collapses)
        np.testing.assert_array_equal(result.meshes.faces, faces)
    assert not np.array_equal(results[7.0].meshes.faces, results[3.0].meshes.faces)  # the option counts here


def test_fast_merged_handles_keep_the_first(tube_meshes):
    ring = np.arange(580, 600)  # the whole top ring, simplified hard: neighbours merge
    result = simplify(tube_meshes, 60, ring, "fast")
    handles, kept = remap_handles(result, ring)
    assert len(handles) < len(ring) and len(np.unique(handles)) == len(handles)
    np.testing.assert_array_equal(handles, result.vertex_map[ring[kept]])
    # each simplified handle stands for the first ring vertex merged into it
    np.testing.assert_array_equal(result.source_vertex[handles], ring[kept])
    unchanged, order = remap_handles(None, ring)
    np.testing.assert_array_equal(unchanged, ring) and np.testing.assert_array_equal(order, np.arange(20))


def test_openmesh_keeps_handles_and_original_positions(tube_meshes):
    ring = np.arange(580, 600)
    result = simplify(tube_meshes, 60, ring, "openmesh")
    assert set(ring) <= set(result.source_vertex)
    handles, kept = remap_handles(result, ring)
    assert len(handles) == len(ring)  # locked: none merged
    for pose, original in zip(poses(result.meshes), poses(tube_meshes)):
        np.testing.assert_array_equal(pose, original[result.source_vertex])


def test_openmesh_keeps_detail_that_moves_in_an_example():
    """A flat grid whose example raises a bump: the rest pose alone says 'flat, remove anything';
    summed over the poses, the error keeps the bump's vertices."""
    vertices, faces = grid(size=24)
    raised = bump(vertices, center=(0.3, 0.6), height=0.3, width=0.08)
    with_example = ExampleMeshes(rest=vertices, faces=faces, examples=(raised,), rest_path="r", example_paths=("e",))
    aware = simplify(with_example, 200, np.array([0]), "openmesh")
    # the same collapses chosen from the rest pose alone, then applied to the example
    from meshik import _core

    kept, rest_faces, *_ = _core.decimate(vertices, faces.astype(np.int32), [], np.array([0], np.int32), 200)
    rest_only_error = surface_distance(raised[kept], rest_faces, raised, faces)
    aware_error = surface_distance(aware.meshes.examples[0], aware.meshes.faces, raised, faces)
    assert aware_error < 0.25 * rest_only_error


def test_openmesh_names_the_non_manifold_triangle():
    vertices, faces = grid(size=5)
    faces = np.concatenate([faces, faces[:1]])  # a triangle twice: its edges have three triangles
    meshes = ExampleMeshes(rest=vertices, faces=faces, examples=(vertices,), rest_path="grid.obj", example_paths=("e",))
    with pytest.raises(PipelineError, match=r"grid.obj: triangle 32 and triangle 0 both run along the edge"):
        simplify(meshes, 10, np.array([0]), "openmesh")


def test_bad_requests():
    vertices, faces = grid(size=5)
    meshes = ExampleMeshes(rest=vertices, faces=faces, examples=(vertices,), rest_path="r", example_paths=("e",))
    with pytest.raises(PipelineError, match="unknown simplifier 'quadric'"):
        simplify(meshes, 10, np.array([0]), "quadric")
    with pytest.raises(PipelineError, match="cannot simplify 32 triangles to 32"):
        simplify(meshes, 32, np.array([0]), "fast")
