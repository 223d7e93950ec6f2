"""The pose filter honours a constraint file's solver options ("blend", "handle_stiffness", ...) as
`meshik pose` does: a file saved by the Drag to Pose tool poses the same in pymeshlab 2025.7 and in
the pipeline, an explicit filter parameter overrides the file, and the solver cache keys on the
options actually used."""
import json
import subprocess
import sys

import numpy as np
import pytest

import meshik
from conftest import SAMPLES
from meshik.inputs import constraints
from meshik.inputs.meshio import load_example_set
from meshik.posing.animation import pose_animation
from plugin_helpers import POSE, apply_refused, load_mesh_set, plugin_path

LIMB = SAMPLES / "limb"
EXAMPLES = [LIMB / f"example_{i}.obj" for i in range(1, 5)]
FILE_OPTIONS = {"blend": "free", "handle_stiffness": 0.5, "region_smoothness": 0.1}


def limb_file(folder, **options):
    """A one-frame constraint file on the limb sample (absolute mesh paths) whose hand is turned 60 degrees
    and pulled 0.4 along x (further than the examples reach, so soft and hard handles differ), with
    the top-level solver options `options`."""
    document = json.loads((LIMB / "animation.json").read_text())
    document.pop("$schema")
    document["rest"] = str(LIMB / "rest.obj")
    document["examples"] = [str(path) for path in EXAMPLES]
    turn = {"axis": [0, 0, 1], "degrees": 60.0, "center": [0.0, 0.0, 0.0]}
    document["frames"] = [{"name": "reach", "targets": {"hand": {"rotate": turn, "translate": [0.4, 0.0, 0.0]},
                                                          "elbow": {"rotate": turn}}}]
    path = folder / "reach.json"
    path.write_text(json.dumps(dict(document, **options)))
    return path


def diagonal_error(actual, expected):
    """The largest vertex distance between two #V by 3 poses over the diagonal of `expected`'s box."""
    diagonal = np.linalg.norm(expected.max(axis=0) - expected.min(axis=0))
    return float(np.linalg.norm(actual - expected, axis=1).max() / diagonal)


def pipeline_pose(path, **overrides):
    """#V by 3: frame 0 of the file posed as `meshik pose` poses it (its options, then `overrides`)."""
    loaded = constraints.load(path)
    meshes = load_example_set(loaded.rest, loaded.examples)
    resolved = constraints.resolve(loaded, meshes.rest)
    options = dict(loaded.solver_options(), **overrides)
    return pose_animation(meshes, resolved.handles, resolved.targets, options, threads=1).vertices[0]


def filter_pose(ms, path, **parameters):
    """(#V by 3 pose, the filter's output values) of the filter on the file's frame 0."""
    ms.set_current_mesh(0)
    output = ms.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame="0", **parameters)
    return ms.mesh(output["layer_id"]).vertex_matrix(), output


def test_file_options_pose_as_meshik_pose_and_parameters_override_them(tmp_path):
    path = limb_file(tmp_path, **FILE_OPTIONS)
    ms = load_mesh_set(LIMB / "rest.obj", EXAMPLES)
    from_file, first = filter_pose(ms, path)
    expected = pipeline_pose(path)
    assert diagonal_error(from_file, expected) < 1e-9
    assert len(first["weights"]) == 1 + len(EXAMPLES)  # the free blend's rest pose, then the examples
    hard_affine = pipeline_pose(path, blend="affine", handle_stiffness=0.0)
    assert diagonal_error(hard_affine, expected) > 1e-3  # the options matter for this frame

    again, second = filter_pose(ms, path)  # same effective options: the factorization is reused
    assert second["factorization_reused"] and np.array_equal(again, from_file)

    overridden, third = filter_pose(ms, path, blend="Affine", handlestiffness=0.0)
    assert not third["factorization_reused"]
    assert diagonal_error(overridden, hard_affine) < 1e-9
    rest, faces = ms.mesh(0).vertex_matrix(), ms.mesh(0).face_matrix()
    examples = [ms.mesh(i).vertex_matrix() for i in range(1, 1 + len(EXAMPLES))]
    resolved = constraints.resolve(constraints.load(path), rest)
    order = np.argsort(resolved.handles)
    solver = meshik.Solver(rest, faces, examples, resolved.handles[order], region_smoothness=0.1, threads=1)
    assert diagonal_error(overridden, solver.solve(resolved.targets[0][order]).vertices) < 1e-9


def test_without_file_options_the_defaults_apply(tmp_path):
    path = limb_file(tmp_path)
    ms = load_mesh_set(LIMB / "rest.obj", EXAMPLES)
    posed, output = filter_pose(ms, path)
    assert len(output["weights"]) == len(EXAMPLES)  # the affine blend
    assert diagonal_error(posed, pipeline_pose(path)) < 1e-9
    for name in ("handlestiffness", "regionsmoothness", "weightregularization"):
        assert name in apply_refused(ms, POSE, targetsource="Constraint file", constraintfile=str(path),
                                     **{name: -0.5})


def test_the_log_says_where_each_option_came_from(tmp_path):
    # pymeshlab prints the log with verbosity on (from C++: read a child process).
    path = limb_file(tmp_path, **FILE_OPTIONS)
    script = "\n".join([
        "import pymeshlab",
        f"pymeshlab.load_plugin({str(plugin_path('double'))!r})",
        "ms = pymeshlab.MeshSet(verbose=True)",
        *[f"ms.load_new_mesh({str(p)!r})" for p in [LIMB / "rest.obj", *EXAMPLES]],
        "ms.set_current_mesh(0)",
        f"ms.apply_filter({POSE!r}, targetsource='Constraint file', constraintfile={str(path)!r}, "
        "handlestiffness=0.25)",
    ])
    child = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True)
    printed = child.stdout + child.stderr
    line = next((l for l in printed.splitlines() if "MeshIK pose: options" in l), None)
    assert line is not None, printed
    for entry in ("feature space nonlinear (constraint file)", "blend free (constraint file)",
                  "region smoothness 0.1 (constraint file)", "handle stiffness 0.25 (parameter)",
                  "weight regularization 0 (default)", "iterations 30 (default)"):
        assert entry in line, line
