"""Issue 26: the constraint file's "handle_stiffness" (soft handles): the reader and schema, the pose it
gives against meshik.Solver(handle_stiffness=), and `meshik pose` / `meshik batch --handle-stiffness`."""
import json

import jsonschema
import numpy as np
import pytest

import meshik
from meshik.cli import main
from meshik.errors import ConstraintError
from meshik.inputs import constraints
from meshik.inputs.meshio import load_example_set
from meshik.posing.animation import pose_animation
from pipeline_meshes import tube_constraints, write_constraints, write_tube_set

STIFFNESS = 0.5


@pytest.fixture(scope="module")
def tube_set(tmp_path_factory):
    """A 120-vertex tube (rest + 2 examples bent about y and about x) in a temporary folder."""
    return write_tube_set(tmp_path_factory.mktemp("stiffness"), rings=12, segments=10)


def unreachable_document(tube_set, frames=2, **settings):
    """The tube's constraint document (`frames` frames) with the top ring pulled 0.3 further along x (a pose
    the examples cannot reach, so soft and hard handles differ), plus settings."""
    document = tube_constraints(tube_set, frames=frames)
    for frame in document["frames"]:
        frame["targets"]["top"] = (np.asarray(frame["targets"]["top"]) + [0.3, 0.0, 0.0]).tolist()
    return dict(document, **settings)


def test_file_stiffness_poses_like_the_solver_option(tube_set):
    path = write_constraints(tube_set["rest"].parent / "soft.json",
                             unreachable_document(tube_set, frames=1, handle_stiffness=STIFFNESS))
    loaded = constraints.load(path)
    assert loaded.solver_options() == {"handle_stiffness": STIFFNESS}
    meshes = load_example_set(loaded.rest, loaded.examples)
    resolved = constraints.resolve(loaded, meshes.rest)
    from_file = pose_animation(meshes, resolved.handles, resolved.targets, loaded.solver_options(), threads=1)
    mesh_set = (meshes.rest, meshes.faces, list(meshes.examples), resolved.handles)
    soft = meshik.Solver(*mesh_set, handle_stiffness=STIFFNESS, threads=1)
    hard = meshik.Solver(*mesh_set, threads=1)
    assert np.abs(from_file.vertices[0] - soft.solve(resolved.targets[0]).vertices).max() < 1e-12
    assert np.abs(from_file.vertices[0] - hard.solve(resolved.targets[0]).vertices).max() > 1e-3


@pytest.mark.parametrize("value, message", [(-1, "handle_stiffness: expected a number >= 0, got -1"),
                                            ("soft", 'handle_stiffness: expected a number, got "soft"')])
def test_bad_stiffness_names_the_file_and_field(tube_set, value, message):
    document = unreachable_document(tube_set, handle_stiffness=value)
    path = write_constraints(tube_set["rest"].parent / "bad_stiffness.json", document)
    with pytest.raises(ConstraintError) as error:
        constraints.load(path)
    assert "bad_stiffness.json" in str(error.value) and message in str(error.value)
    schema = jsonschema.Draft202012Validator(json.loads(constraints.SCHEMA_PATH.read_text()))
    assert list(schema.iter_errors(document))
    assert list(schema.iter_errors(unreachable_document(tube_set, handle_stiffness=2))) == []


def test_meshik_pose_and_batch_take_the_stiffness(tube_set, tmp_path):
    """pose --handle-stiffness overrides the file's; batch --handle-stiffness applies where the file sets none."""
    folder = tube_set["rest"].parent
    says = write_constraints(folder / "says.json", unreachable_document(tube_set, handle_stiffness=STIFFNESS))
    silent = write_constraints(folder / "silent.json", unreachable_document(tube_set))
    assert main(["pose", str(says), "--out", str(tmp_path / "pose"), "--format", "ply", "--quiet",
                 "--handle-stiffness", "2"]) == 0
    assert json.loads((tmp_path / "pose" / "report.json").read_text())["solver"]["handle_stiffness"] == 2.0
    assert main(["batch", str(says), str(silent), "--out", str(tmp_path / "batch"), "--jobs", "1", "--format", "ply",
                 "--quiet", "--handle-stiffness", "3"]) == 0
    stiffness = {name: json.loads((tmp_path / "batch" / name / "report.json").read_text())["solver"]["handle_stiffness"]
                 for name in ("says", "silent")}
    assert stiffness == {"says": STIFFNESS, "silent": 3.0}
