"""The MeshIK filters loaded into pymeshlab 2025.7 give the Python API's results (meshik.Solver,
meshik.ExampleSet) for the same meshes, handles and targets, on the samples and on the horse."""
import json
import re
import subprocess
import sys

import numpy as np
import pymeshlab
import pytest

import meshik
from conftest import SAMPLES, example_set_files
from plugin_helpers import (BLEND, POSE, apply_refused, layer_arrays, load_mesh_set, mesh_set, plugin_path,
                            relative_error, select_vertices, spread_vertices)

SAMPLE_SETS = ["bar", "flag", "limb"]


def sample_files(name):
    """(rest.obj, [example_1.obj, ...]) of a sample set, examples in numeric order."""
    folder = SAMPLES / name
    examples = sorted(folder.glob("example_*.obj"), key=lambda p: int(p.stem.split("_")[-1]))
    return folder / "rest.obj", examples


def load_sample(name):
    """(MeshSet with rest + example layers, rest #V by 3, faces, [examples])."""
    rest_path, example_paths = sample_files(name)
    ms = load_mesh_set(rest_path, example_paths)
    return (ms, *layer_arrays(ms, 1 + len(example_paths)))


def python_pose(rest, faces, examples, handles, targets, **options):
    """meshik.Solver's result for the same inputs (the plugin's defaults unless given)."""
    options = {"feature_space": "nonlinear", "weight_regularization": 0.0, "max_iterations": 30,
               "tolerance": 1e-10, **options}
    return meshik.Solver(rest, faces, examples, handles, **options).solve(targets)


def assert_same_pose(ms, output, expected):
    """The filter's pose layer and returned values equal the Python API's result."""
    posed = ms.mesh(output["layer_id"]).vertex_matrix()
    assert relative_error(posed, expected.vertices) < 1e-9
    np.testing.assert_allclose(output["weights"], expected.weights, rtol=1e-9, atol=1e-12)
    assert output["iterations"] == expected.iterations
    assert output["residual"] == pytest.approx(expected.residual, rel=1e-6, abs=1e-12)
    assert output["inverted_triangles"] == len(expected.inverted_triangles)


@pytest.mark.parametrize("name", SAMPLE_SETS)
def test_pose_from_constraint_file_equals_python_api(name):
    constraints = pytest.importorskip("meshik.inputs.constraints", reason="the pipeline's constraint-file reader")
    ms, rest, faces, examples = load_sample(name)
    path = SAMPLES / name / "animation.json"
    resolved = constraints.resolve(constraints.load(path), rest)
    frame = len(resolved.frame_names) // 2
    output = ms.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame=str(frame))
    order = np.argsort(resolved.handles)
    expected = python_pose(rest, faces, examples, resolved.handles[order], resolved.targets[frame][order])
    assert_same_pose(ms, output, expected)
    # The frame can also be named.
    by_name = ms.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path),
                              frame=resolved.frame_names[frame])
    assert relative_error(ms.mesh(by_name["layer_id"]).vertex_matrix(), expected.vertices) < 1e-12


def test_pose_takes_the_constraint_file_vertex_group_regions(tmp_path):
    constraints = pytest.importorskip("meshik.inputs.constraints", reason="the pipeline's constraint-file reader")
    ms, rest, faces, examples = load_sample("limb")
    rest_path, example_paths = sample_files("limb")
    document = json.loads((SAMPLES / "limb" / "animation.json").read_text())
    low = np.flatnonzero(rest[:, 1] < np.median(rest[:, 1]))
    document.update(rest=str(rest_path), examples=[str(p) for p in example_paths],
                    regions={"low": low[: len(low) // 2].tolist(), "middle": low[len(low) // 2:].tolist()})
    path = tmp_path / "grouped.json"
    path.write_text(json.dumps(document))
    resolved = constraints.resolve(constraints.load(path), rest)
    output = ms.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame="1")
    ids = constraints.region_vertex_groups(document["regions"], len(rest), path)
    order = np.argsort(resolved.handles)
    expected = python_pose(rest, faces, examples, resolved.handles[order], resolved.targets[1][order], regions=ids)
    assert len(expected.weights) == 3 * len(examples)  # two groups and the vertices in none
    # The same pose; the weights of these handle-poor regions are ill-conditioned (agree to 1e-6, not 1e-9).
    assert relative_error(ms.mesh(output["layer_id"]).vertex_matrix(), expected.vertices) < 1e-9
    np.testing.assert_allclose(output["weights"], expected.weights, rtol=1e-6, atol=1e-9)
    assert output["iterations"] == expected.iterations
    document["regions"] = {"low": [len(rest)]}
    path.write_text(json.dumps(document))
    message = apply_refused(ms, POSE, targetsource="Constraint file", constraintfile=str(path), frame="1")
    assert f"regions.low: vertex {len(rest)} is out of range" in message


def test_pose_from_target_layer_equals_python_api_on_horse(shared_data):
    rest_path, example_paths = example_set_files(shared_data / "horse-poses")
    _, gallop_paths = example_set_files(shared_data / "horse-gallop")
    ms = load_mesh_set(rest_path, example_paths)
    rest, faces, examples = layer_arrays(ms, 1 + len(example_paths))
    ms.load_new_mesh(str(gallop_paths[len(gallop_paths) // 3]))
    target = ms.current_mesh()
    ms.set_current_mesh(0)
    handles = spread_vertices(rest, 20)
    select_vertices(ms, handles)
    output = ms.apply_filter(POSE, targetsource="Target layer", targetmesh=target.id())
    assert len(output["weights"]) == len(example_paths)  # the target layer is no example
    expected = python_pose(rest, faces, examples, handles, target.vertex_matrix()[handles])
    assert_same_pose(ms, output, expected)


def rigid_transform(degrees: float, axis: int, translation) -> np.ndarray:
    """4x4 rotation about a coordinate axis followed by a translation."""
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    i, j = [k for k in range(3) if k != axis]
    matrix = np.eye(4)
    matrix[i, i], matrix[i, j], matrix[j, i], matrix[j, j] = c, -s, s, c
    matrix[:3, 3] = translation
    return matrix


def test_pose_from_handle_transform_with_options_equals_python_api():
    ms, rest, faces, examples = load_sample("limb")
    handles = spread_vertices(rest, 12)
    select_vertices(ms, handles)
    matrix = rigid_transform(25.0, 2, [0.1, -0.2, 0.05])
    output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=matrix, featurespace="Linear",
                             weightregularization=0.25, iterations=7)
    targets = rest[handles] @ matrix[:3, :3].T + matrix[:3, 3]
    expected = python_pose(rest, faces, examples, handles, targets, feature_space="linear",
                           weight_regularization=0.25, max_iterations=7)
    assert_same_pose(ms, output, expected)


def test_pose_with_free_blend_and_regions_equals_python_api():
    ms, rest, faces, examples = load_sample("limb")
    handles = spread_vertices(rest, 12)
    select_vertices(ms, handles)
    matrix = rigid_transform(25.0, 2, [0.1, -0.2, 0.05])
    output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=matrix, blend="Free", regions=3,
                             regionsmoothness=0.5)
    targets = rest[handles] @ matrix[:3, :3].T + matrix[:3, 3]
    expected = python_pose(rest, faces, examples, handles, targets, blend="free", regions=3, region_smoothness=0.5)
    assert len(expected.weights) == 3 * (1 + len(examples))  # the free blend's rest pose, then the examples
    assert_same_pose(ms, output, expected)
    assert "regions" in apply_refused(ms, POSE, targetsource="Handle transform", handletransform=matrix, regions=-2)


def test_pose_with_soft_handles_equals_python_api():
    ms, rest, faces, examples = load_sample("limb")
    handles = spread_vertices(rest, 12)
    select_vertices(ms, handles)
    matrix = rigid_transform(25.0, 2, [0.1, -0.2, 0.05])
    output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=matrix, handlestiffness=0.5)
    targets = rest[handles] @ matrix[:3, :3].T + matrix[:3, 3]
    assert_same_pose(ms, output, python_pose(rest, faces, examples, handles, targets, handle_stiffness=0.5))
    assert "handlestiffness" in apply_refused(ms, POSE, targetsource="Handle transform", handletransform=matrix,
                                              handlestiffness=-0.5)


def test_pose_is_the_same_for_any_thread_count_and_a_negative_count_is_refused():
    ms, rest, faces, examples = load_sample("limb")
    handles = spread_vertices(rest, 12)
    select_vertices(ms, handles)
    matrix = rigid_transform(40.0, 1, [0.2, 0.1, -0.1])
    poses = []
    for threads in (1, 2, 0):
        output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=matrix, threads=threads)
        poses.append(ms.mesh(output["layer_id"]).vertex_matrix())
        ms.set_current_mesh(0)
    assert all(np.array_equal(poses[0], pose) for pose in poses[1:])
    targets = rest[handles] @ matrix[:3, :3].T + matrix[:3, 3]
    assert relative_error(poses[0], python_pose(rest, faces, examples, handles, targets).vertices) < 1e-9
    assert "threads" in apply_refused(ms, POSE, targetsource="Handle transform", handletransform=matrix, threads=-1)


def test_pose_layer_keeps_selection_and_rest_stays_current():
    ms, rest, _, examples = load_sample("bar")
    handles = spread_vertices(rest, 6)
    select_vertices(ms, handles)
    turn = rigid_transform(10, 1, [0, 0, 0])
    output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=turn)
    assert ms.current_mesh().id() == 0
    assert ms.mesh(output["layer_id"]).label() == f"MeshIK pose of {ms.mesh(0).label()}"
    assert list(np.flatnonzero(ms.mesh(output["layer_id"]).vertex_selection_array())) == list(handles)
    np.testing.assert_array_equal(ms.mesh(0).vertex_matrix(), rest)
    # Run again: the earlier output layer is not taken as an example.
    again = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=turn)
    assert len(again["weights"]) == len(examples)


def test_pose_in_place_writes_the_rest_layer():
    ms, rest, faces, examples = load_sample("bar")
    handles = spread_vertices(rest, 6)
    select_vertices(ms, handles)
    layers = ms.mesh_number()
    matrix = rigid_transform(-15, 0, [0, 0.1, 0])
    output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=matrix, inplace=True)
    assert output["layer_id"] == 0 and ms.mesh_number() == layers
    targets = rest[handles] @ matrix[:3, :3].T + matrix[:3, 3]
    assert_same_pose(ms, output, python_pose(rest, faces, examples, handles, targets))
    assert list(np.flatnonzero(ms.mesh(0).vertex_selection_array())) == list(handles)


def test_rerun_with_same_handles_reuses_the_factorization():
    ms, rest, _, _ = load_sample("flag")
    path = SAMPLES / "flag" / "animation.json"
    frames = len(json.loads(path.read_text())["frames"])
    first = ms.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame="1")
    second = ms.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame=str(frames - 1))
    assert second["factorization_reused"]
    posed_first, posed_second = (ms.mesh(out["layer_id"]).vertex_matrix() for out in (first, second))
    assert relative_error(posed_second, posed_first) > 1e-6
    select_vertices(ms, spread_vertices(rest, 5))
    other = ms.apply_filter(POSE, targetsource="Handle transform",
                            handletransform=rigid_transform(5, 2, [0, 0, 0]))
    assert not other["factorization_reused"]
    other_again = ms.apply_filter(POSE, targetsource="Handle transform",
                                  handletransform=rigid_transform(9, 2, [0, 0, 0]))
    assert other_again["factorization_reused"]


@pytest.mark.parametrize("name", SAMPLE_SETS)
def test_blend_with_a_unit_weight_reproduces_that_example(name):
    ms, _, _, examples = load_sample(name)
    for i, example in enumerate(examples):
        weights = ", ".join("1" if k == i else "0" for k in range(len(examples)))
        output = ms.apply_filter(BLEND, weights=weights)
        # To the rounding of the features, stored in single precision (measured 2.4e-9 on the bar).
        assert relative_error(ms.mesh(output["layer_id"]).vertex_matrix(), example) < 1e-7


@pytest.mark.parametrize("feature_space", ["Nonlinear", "Linear"])
def test_blend_equals_python_api(feature_space):
    ms, rest, faces, examples = load_sample("flag")
    weights = np.linspace(-0.3, 0.9, len(examples))
    output = ms.apply_filter(BLEND, weights=", ".join(repr(float(w)) for w in weights), featurespace=feature_space)
    expected = meshik.ExampleSet(rest, faces, examples).blend(weights, feature_space.lower())
    assert relative_error(ms.mesh(output["layer_id"]).vertex_matrix(), expected) < 1e-9


def test_example_layers_parameter_restricts_the_examples():
    ms, rest, faces, examples = load_sample("flag")
    handles = spread_vertices(rest, 8)
    select_vertices(ms, handles)
    matrix = rigid_transform(20, 1, [0, 0, 0])
    output = ms.apply_filter(POSE, examplelayers="example_2.obj, 4", targetsource="Handle transform",
                             handletransform=matrix)
    targets = rest[handles] @ matrix[:3, :3].T + matrix[:3, 3]
    assert_same_pose(ms, output, python_pose(rest, faces, [examples[1], examples[3]], handles, targets))


def test_parameter_lists_document_every_parameter():
    # pymeshlab prints from C++ (std::cout): read it from a child process.
    expected = {
        POSE: ["examplelayers : str", "featurespace : str", "targetsource : str", "targetmesh : int",
               "constraintfile : str", "frame : str", "handletransform : numpy.ndarray[numpy.float64[4, 4]]",
               "iterations : int", "weightregularization : float", "blend : str", "regions : int",
               "regionsmoothness : float", "handlestiffness : float", "inplace : bool", "threads : int"],
        BLEND: ["examplelayers : str", "featurespace : str", "weights : str"],
    }
    for name, parameters in expected.items():
        script = (f"import pymeshlab; pymeshlab.load_plugin({str(plugin_path('double'))!r}); "
                  f"pymeshlab.print_filter_parameter_list({name!r})")
        printed = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True).stdout
        listed = [line.strip().split(" = ")[0] for line in printed.splitlines() if " : " in line]
        assert listed == parameters, printed


def test_progress_reaches_the_hosts_callback():
    # pymeshlab prints the callback's messages with verbosity on (from C++: read a child process).
    rest_path, example_paths = sample_files("bar")
    script = "\n".join([
        "import pymeshlab",
        f"pymeshlab.load_plugin({str(plugin_path('double'))!r})",
        "ms = pymeshlab.MeshSet(verbose=True)",
        *[f"ms.load_new_mesh({str(p)!r})" for p in [rest_path, *example_paths]],
        "ms.set_current_mesh(0)",
        f"ms.apply_filter({POSE!r}, targetsource='Constraint file', "
        f"constraintfile={str(SAMPLES / 'bar' / 'animation.json')!r}, frame='5')",
    ])
    child = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True)
    printed = child.stdout + child.stderr
    progress = re.findall(r"MeshIK: ([^\[\n]+?)\s+\[ (\d+)% \]", printed)
    stages = [stage for stage, _ in progress]
    assert "example features" in stages and "factorizing" in stages, printed
    assert any(stage.startswith("Gauss-Newton iteration") for stage in stages), printed
    percents = [int(percent) for _, percent in progress]
    assert percents == sorted(percents) and percents[-1] <= 99, printed


def test_filters_work_on_meshes_built_in_python():
    # Layers made from arrays (no files) work the same: a bent strip and its example.
    strip = np.array([[x, y, 0.0] for x in range(6) for y in range(2)], dtype=float)
    faces = np.array([[2 * i, 2 * i + 2, 2 * i + 1] for i in range(5)]
                     + [[2 * i + 1, 2 * i + 2, 2 * i + 3] for i in range(5)])
    bent = strip.copy()
    bent[:, 2] = 0.1 * strip[:, 0] ** 2
    ms = mesh_set(strip, faces, [bent])
    output = ms.apply_filter(BLEND, weights="0.5")
    expected = meshik.ExampleSet(strip, faces, [bent]).blend(np.array([0.5]), "nonlinear")
    assert relative_error(ms.mesh(output["layer_id"]).vertex_matrix(), expected) < 1e-9
