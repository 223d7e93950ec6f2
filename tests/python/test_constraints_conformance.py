"""The conformance fixtures (tests/constraints_conformance) through the Python API, `meshik validate`,
the MeshLab plugin in pymeshlab and the JSON Schema: every bad file is refused by each with the same
message (by the schema where the fault is structural), every good file resolves to the same handles
and targets everywhere. tests/cpp/test_constraints_conformance.cpp runs them through the C++ library."""
import json
import pathlib

import jsonschema
import numpy as np
import pytest

from meshik.inputs import constraints
from meshik.cli import main
from meshik.errors import ConstraintError
from plugin_helpers import POSE, apply_refused, load_mesh_set

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "tests" / "constraints_conformance"
EXPECTED = json.loads((FIXTURES / "expected.json").read_text())
BAD = sorted(EXPECTED["bad"])
GOOD = sorted(EXPECTED["good"])
GRID = FIXTURES / "grid"


@pytest.fixture(scope="module")
def rest_vertices():
    """#V by 3 vertices of the fixtures' rest grid, read from its OBJ "v" lines."""
    lines = (GRID / "rest.obj").read_text().splitlines()
    return np.array([[float(x) for x in line.split()[1:4]] for line in lines if line.startswith("v ")])


@pytest.fixture(scope="module")
def schema():
    """A draft 2020-12 validator of the packaged schema (the schema itself checked first)."""
    document = json.loads(constraints.SCHEMA_PATH.read_text())
    jsonschema.Draft202012Validator.check_schema(document)
    return jsonschema.Draft202012Validator(document)


def expected_message(name):
    """The full message for bad file `name`: its path, then the expected problem."""
    return f"{FIXTURES / 'bad' / name}: {EXPECTED['bad'][name]['message']}"


def test_fixtures_cover_both_kinds_and_every_stage():
    assert len(BAD) >= 40 and len(GOOD) >= 6
    assert {EXPECTED["bad"][n]["stage"] for n in BAD} == {"read", "resolve"}
    assert sum(EXPECTED["bad"][n]["structural"] for n in BAD) >= 20
    assert sorted(p.name for p in (FIXTURES / "bad").glob("*.json")) == BAD
    assert sorted(p.name for p in (FIXTURES / "good").glob("*.json")) == GOOD


@pytest.mark.parametrize("name", BAD)
def test_python_api_refuses_bad_file(name, rest_vertices):
    with pytest.raises(ConstraintError) as raised:
        constraints.resolve(constraints.load(FIXTURES / "bad" / name), rest_vertices)
    assert str(raised.value) == expected_message(name)


@pytest.mark.parametrize("name", GOOD)
def test_python_api_resolves_good_file(name, rest_vertices):
    expected = EXPECTED["good"][name]
    resolved = constraints.resolve(constraints.load(FIXTURES / "good" / name), rest_vertices)
    assert list(resolved.frame_names) == expected["frame_names"]
    np.testing.assert_array_equal(resolved.handles, expected["handles"])
    np.testing.assert_allclose(resolved.targets, np.array(expected["targets"]), rtol=0, atol=1e-12)


def test_validate_command_prints_the_problem_of_every_bad_file(capsys):
    paths = [str(FIXTURES / "bad" / name) for name in BAD] + [str(FIXTURES / "good" / name) for name in GOOD]
    assert main(["validate", *paths]) == 1
    printed = capsys.readouterr().out.splitlines()
    for name in BAD:  # one message per fixture (each has one fault)
        assert printed.count(expected_message(name)) == 1, name
    for name in GOOD:
        assert f"{FIXTURES / 'good' / name}: OK" in printed
    assert len(printed) == len(BAD) + len(GOOD)


@pytest.mark.parametrize("name", GOOD)
def test_schema_accepts_good_file(name, schema):
    errors = list(schema.iter_errors(json.loads((FIXTURES / "good" / name).read_text())))
    assert errors == []


@pytest.mark.parametrize("name", [n for n in BAD if EXPECTED["bad"][n]["structural"]])
def test_schema_refuses_structural_fault(name, schema):
    assert list(schema.iter_errors(json.loads((FIXTURES / "bad" / name).read_text())))


def test_sample_files_reference_the_schema_and_pass_it(schema):
    samples = sorted((ROOT / "sample_meshes").glob("*/animation.json"))
    assert samples
    for path in samples:
        document = json.loads(path.read_text())
        assert (path.parent / document["$schema"]).resolve() == constraints.SCHEMA_PATH
        assert list(schema.iter_errors(document)) == []
        assert constraints.validate(path) == []


@pytest.fixture(scope="module")
def grid_layers():
    """The fixtures' grid (rest, two examples) as MeshLab layers with the plugin loaded."""
    return load_mesh_set(GRID / "rest.obj", [GRID / "example_1.obj", GRID / "example_2.obj"])


def last_frame(path):
    """The 0-based index of the file's last frame, as the plugin's "frame" parameter ("0" when unreadable)."""
    try:
        frames = json.loads(path.read_text())["frames"]
        return str(max(len(frames) - 1, 0))
    except (ValueError, KeyError, TypeError):
        return "0"


@pytest.mark.parametrize("name", BAD)
def test_plugin_refuses_bad_file(name, grid_layers):
    path = FIXTURES / "bad" / name
    grid_layers.set_current_mesh(0)
    grid_layers.set_selection_none()
    message = apply_refused(grid_layers, POSE, targetsource="Constraint file", constraintfile=str(path),
                            frame=last_frame(path))
    assert expected_message(name) in message


@pytest.mark.parametrize("name", GOOD)
def test_plugin_poses_good_file_onto_its_targets(name, grid_layers, rest_vertices):
    path = FIXTURES / "good" / name
    expected = EXPECTED["good"][name]
    grid_layers.set_current_mesh(0)
    grid_layers.set_selection_none()
    assert np.array_equal(grid_layers.mesh(0).vertex_matrix(), rest_vertices)  # the same rest mesh as above
    output = grid_layers.apply_filter(POSE, targetsource="Constraint file", constraintfile=str(path), frame=last_frame(path))
    posed = grid_layers.mesh(output["layer_id"]).vertex_matrix()
    np.testing.assert_allclose(posed[expected["handles"]], np.array(expected["targets"][-1]), rtol=0, atol=1e-9)
