"""Both decimators' distance bound (OpenMesh's ModPoseDistance, the fast one's DistanceGuard): in every
pose, no removed vertex ends farther than the bound from the simplified surface, nor a simplified
triangle's centroid from the original surface; simplify relaxes the bound when the target cannot be
reached under it."""
import numpy as np
import pytest

from meshik import _core
from meshik.inputs.meshio import ExampleMeshes
from meshik.posing import simplify as simplify_module
from meshik.posing.surface_distance import point_triangle_distance
from pipeline_meshes import bend, tube

LOCKED = np.array([0, 599], dtype=np.int32)
DECIMATORS = pytest.mark.parametrize("decimate, method", [(_core.decimate, "openmesh"), (_core.decimate_fast, "fast")])


@pytest.fixture(scope="module")
def bent_tube():
    """(rest #V by 3, triangles #F by 3 int32, [two bent examples]) of a 600-vertex tube."""
    vertices, faces = tube(rings=30, segments=20)
    return vertices, faces.astype(np.int32), [bend(vertices, 90, "y"), bend(vertices, 90, "x")]


def distance_to_surface(points: np.ndarray, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """#P distances from each point (#P by 3) to the nearest triangle of (vertices #V by 3, faces #F by 3)."""
    corners = vertices[faces]
    count = len(faces)
    distances = point_triangle_distance(np.repeat(points, count, axis=0), *(np.tile(corners[:, k], (len(points), 1))
                                                                          for k in range(3)))
    return distances.reshape(len(points), count).min(axis=1)


@DECIMATORS
def test_bound_holds_both_ways_in_every_pose(bent_tube, decimate, method):
    rest, faces, examples = bent_tube
    *_, unbounded, _, _ = decimate(rest, faces, examples, LOCKED, 150)
    kept, simplified, _, worst, bound, relaxations = decimate(rest, faces, examples, LOCKED, 150,
                                                                    max_distance=0.5 * unbounded)
    assert len(simplified) <= 150 and worst <= bound == pytest.approx(0.5 * unbounded * 1.25 ** relaxations)
    for pose in [rest] + examples:
        assert distance_to_surface(pose, pose[kept], simplified).max() <= bound * (1 + 1e-9)
        centroids = pose[kept][simplified].mean(axis=1)
        assert distance_to_surface(centroids, pose, faces).max() <= bound * (1 + 1e-9)


@DECIMATORS
def test_tight_bound_stalls_then_relaxes(bent_tube, decimate, method):
    rest, faces, examples = bent_tube
    _, free, _, unbounded, _, _ = decimate(rest, faces, examples, LOCKED, 150)
    assert len(free) <= 150
    _, relaxed, _, worst, bound, relaxations = decimate(rest, faces, examples, LOCKED, 150,
                                                              max_distance=0.1 * unbounded, relax_factor=1.5)
    assert len(relaxed) <= 150 and relaxations >= 1 and worst <= bound == pytest.approx(0.1 * unbounded * 1.5 ** relaxations)


@DECIMATORS
def test_worst_distance_bounds_the_vertices_distance(bent_tube, decimate, method):
    rest, faces, _ = bent_tube
    kept, simplified, _, worst, _, _ = decimate(rest, faces, [], LOCKED, 150)
    true_worst = distance_to_surface(rest, rest[kept], simplified).max()
    assert 0 < true_worst <= worst * (1 + 1e-9)


@DECIMATORS
def test_simplify_bounds_by_the_rest_error(bent_tube, monkeypatch, decimate, method):
    rest, faces, examples = bent_tube
    meshes = ExampleMeshes(rest=rest, faces=faces.astype(np.int64), examples=tuple(examples), rest_path="r",
                           example_paths=("a", "b"))
    *_, rest_error, _, _ = decimate(rest, faces, [], LOCKED, 150)
    result = simplify_module.simplify(meshes, 150, LOCKED, method)
    factor, relax = simplify_module.DISTANCE_BOUND_FACTOR, simplify_module.RELAX_FACTOR
    assert rest_error < 1e-9  # a straight tube: the rest alone loses nothing, the bent examples must relax it
    assert len(result.meshes.faces) <= 150
    assert result.distance_bound >= factor * rest_error * relax ** result.relaxations * (1 - 1e-12)
    assert result.relaxations == 0 or np.isfinite(result.distance_bound)  # relaxed, not lifted
    monkeypatch.setattr(simplify_module, "MAX_RELAXATIONS", 0)
    lifted = simplify_module.simplify(meshes, 150, LOCKED, method)
    assert len(lifted.meshes.faces) <= 150
    assert np.isinf(lifted.distance_bound) == (result.relaxations > 0)


@DECIMATORS
def test_bad_bounds(bent_tube, decimate, method):
    rest, faces, examples = bent_tube
    with pytest.raises(ValueError, match="the distance bound must be positive"):
        decimate(rest, faces, examples, LOCKED, 150, max_distance=0.0)
    with pytest.raises(ValueError, match="relax factor must exceed 1"):
        decimate(rest, faces, examples, LOCKED, 150, max_distance=1.0, relax_factor=1.0)
