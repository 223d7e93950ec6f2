"""meshik._core on the real example sets (../shared/data; skipped when absent) and on the project's
generated sample sets (sample_meshes/; skipped when absent): examples are reproduced from their own
handles, and a held-out pose is approached better, with fewer folded triangles, by the nonlinear
space than by the linear one."""
import pathlib

import numpy as np
import pytest

import meshik
from conftest import example_set_files


def read_obj(path):
    """(vertices (n, 3) float64, faces (m, 3) int64) of a triangle OBJ with 1-based indices."""
    vertices, faces = [], []
    with open(path) as lines:
        for line in lines:
            if line.startswith("v "):
                vertices.append(line.split()[1:4])
            elif line.startswith("f "):
                faces.append([corner.split("/")[0] for corner in line.split()[1:4]])
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64) - 1


def farthest_points(vertices, count):
    """count vertex indices spread by farthest-point sampling from vertex 0."""
    chosen = [0]
    distance = np.linalg.norm(vertices - vertices[0], axis=1)
    while len(chosen) < count:
        chosen.append(int(np.argmax(distance)))
        distance = np.minimum(distance, np.linalg.norm(vertices - vertices[chosen[-1]], axis=1))
    return np.array(chosen)


def test_horse_held_out_pose_is_closer_in_the_nonlinear_space(shared_data):
    rest_path, pose_paths = example_set_files(shared_data / "horse-poses")
    rest, faces = read_obj(rest_path)
    poses = [read_obj(p)[0] for p in pose_paths]
    examples, held_out = poses[:4], poses[4]
    example_set = meshik.ExampleSet(rest, faces, examples)
    handles = farthest_points(rest, 16)
    errors = {}
    for space in ("nonlinear", "linear"):
        result = meshik.Solver.from_example_set(example_set, handles, feature_space=space).solve(held_out[handles])
        assert result.converged and result.vertices.shape == rest.shape
        np.testing.assert_allclose(result.vertices[handles], held_out[handles], atol=1e-12)
        errors[space] = np.sqrt(np.mean(np.sum((result.vertices - held_out) ** 2, axis=1)))
    assert errors["nonlinear"] < errors["linear"]


def test_lion_example_is_reproduced_from_its_handles(shared_data):
    rest_path, pose_paths = example_set_files(shared_data / "lion-poses")
    rest, faces = read_obj(rest_path)
    examples = [read_obj(p)[0] for p in pose_paths[:5]]
    handles = farthest_points(rest, 12)
    solver = meshik.Solver(rest, faces, np.stack(examples), handles)
    result = solver.solve(examples[3][handles])
    diagonal = np.linalg.norm(np.ptp(rest, axis=0))
    assert np.abs(result.vertices - examples[3]).max() < 1e-6 * diagonal
    np.testing.assert_allclose(result.weights, np.eye(5)[3], atol=1e-6)


def test_single_precision_features_pose_the_held_out_horse_like_double_ones(shared_data):
    """Issue 13's rule for features stored in single precision (the default): the examples still
    reproduce to < 1e-6 of the bounding-box diagonal and the held-out pose's error stays within 1e-4
    relative of the one with features stored in double."""
    rest_path, pose_paths = example_set_files(shared_data / "horse-poses")
    rest, faces = read_obj(rest_path)
    poses = [read_obj(p)[0] for p in pose_paths]
    examples, held_out = poses[:4], poses[4]
    handles = farthest_points(rest, 16)
    diagonal = np.linalg.norm(np.ptp(rest, axis=0))
    errors = {}
    for precision in ("single", "double"):
        example_set = meshik.ExampleSet(rest, faces, examples, feature_precision=precision)
        assert example_set.feature_precision == precision
        solver = meshik.Solver.from_example_set(example_set, handles)
        for example in examples:
            assert np.abs(solver.solve(example[handles]).vertices - example).max() < 1e-6 * diagonal
        result = solver.solve(held_out[handles])
        errors[precision] = np.sqrt(np.mean(np.sum((result.vertices - held_out) ** 2, axis=1)))
    assert meshik.ExampleSet(rest, faces, examples).feature_precision == "single"
    assert abs(errors["single"] - errors["double"]) <= 1e-4 * errors["double"], errors


def sample_sets(samples_dir):
    """The generated sample folders (rest.obj and example_*.obj), or a skip."""
    folders = sorted(p for p in samples_dir.glob("*") if (p / "rest.obj").exists()) if samples_dir.is_dir() else []
    if not folders:
        pytest.skip(f"no generated sample sets in {samples_dir}")
    return folders


def test_sample_sets_reproduce_every_example(samples_dir):
    for folder in sample_sets(samples_dir):
        rest, faces = read_obj(folder / "rest.obj")
        examples = [read_obj(p)[0] for p in sorted(folder.glob("example_*.obj"))]
        handles = farthest_points(rest, min(12, len(rest)))
        for space in ("nonlinear", "linear"):
            solver = meshik.Solver(rest, faces, examples, handles, feature_space=space)
            for i, example in enumerate(examples):
                result = solver.solve(example[handles])
                scale = np.linalg.norm(np.ptp(rest, axis=0))
                assert np.abs(result.vertices - example).max() < 1e-6 * scale, (folder.name, space, i)


def facing_against(result, truth, faces):
    """Number of triangles whose normal in `result` points against their normal in `truth` (#V by 3 each)."""
    def normals(v):
        return np.cross(v[faces[:, 1]] - v[faces[:, 0]], v[faces[:, 2]] - v[faces[:, 0]])
    return int(np.sum(np.einsum("ij,ij->i", normals(result), normals(truth)) < 0))


def test_horse_pose_covered_by_the_examples_is_posed_without_flips(shared_data):
    """Horse pose 10 held out, poses 1-9 as examples, 16 handles at its positions: the nonlinear
    space lands closer than the linear one, flips no triangle against the true pose (the linear
    space flips some) and turns none over against its own blended deformation. Pose 10 is the held-out pose that the other nine examples cover: for other
    poses, some triangles already flip in the examples' own handle-free blend, because the horse
    examples contain sharply creased regions that no blend of them can undo (see the solver notes)."""
    rest_path, pose_paths = example_set_files(shared_data / "horse-poses")
    rest, faces = read_obj(rest_path)
    poses = [read_obj(p)[0] for p in pose_paths]
    truth = poses[9]
    example_set = meshik.ExampleSet(rest, faces, poses[:9])
    handles = farthest_points(rest, 16)
    flips, errors, inverted = {}, {}, {}
    for space in ("nonlinear", "linear"):
        result = meshik.Solver.from_example_set(example_set, handles, feature_space=space).solve(truth[handles])
        flips[space] = facing_against(result.vertices, truth, faces)
        inverted[space] = len(result.inverted_triangles)
        errors[space] = np.sqrt(np.mean(np.sum((result.vertices - truth) ** 2, axis=1)))
    assert flips["nonlinear"] == 0 and flips["linear"] > 0, flips
    assert errors["nonlinear"] < errors["linear"], errors
    assert inverted["nonlinear"] == 0, inverted


@pytest.mark.parametrize("folder", ["lion-poses", "cat-poses"])
def test_held_out_poses_fold_fewer_triangles_in_the_nonlinear_space(shared_data, folder):
    """Each pose held out in turn (the others are the examples), 16 handles at its positions: summed
    over the poses, the nonlinear space turns far fewer faces over against their blended
    deformation than the linear space (measured: lion 892 against 1,947, cat 1,627 against 4,501;
    the folds left sit beside handles the examples cannot follow and where extrapolated weights
    blend incompatible features)."""
    rest_path, pose_paths = example_set_files(shared_data / folder)
    rest, faces = read_obj(rest_path)
    poses = [read_obj(p)[0] for p in pose_paths]
    handles = farthest_points(rest, 16)
    inverted = {"nonlinear": 0, "linear": 0}
    for held in range(len(poses)):
        example_set = meshik.ExampleSet(rest, faces, [p for i, p in enumerate(poses) if i != held])
        for space in inverted:
            result = meshik.Solver.from_example_set(example_set, handles, feature_space=space).solve(poses[held][handles])
            inverted[space] += len(result.inverted_triangles)
    assert inverted["nonlinear"] < 0.6 * inverted["linear"], inverted
