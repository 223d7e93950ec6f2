"""Constraint files: a full valid file, resolution to arrays, every schema error naming its JSON
path, and a fuzzer that feeds the loader random and mutated documents."""
import copy
import json
import math
import pathlib

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from meshik.inputs import constraints
from meshik.errors import ConstraintError
from pipeline_meshes import bend, tube_constraints, write_constraints, write_tube_set


@pytest.fixture(scope="module")
def tube_set(tmp_path_factory):
    """A small tube example set (rest + 2 bent examples) in a temporary folder."""
    return write_tube_set(tmp_path_factory.mktemp("tube"), rings=6, segments=6)


@pytest.fixture()
def document(tube_set):
    """A valid constraint document exercising every kind of handle and target."""
    doc = tube_constraints(tube_set, frames=2)
    doc["handles"]["ring"] = {"near": [0.0, 0.0, 2.4], "radius": 0.6}
    doc["feature_space"] = "linear"
    doc["fps"] = 30
    doc["frames"].append({"name": "rigid", "targets": {"top": {"translate": [0, 0, 1]},
                                                       "ring": {"rotate": {"axis": [0, 0, 1], "degrees": 90}}}})
    doc["frames"].append({"targets": {"top": {"matrix": [[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
                                      "ring": {"rotate": {"axis": [1, 0, 0], "degrees": 180, "center": [0, 0, 0]},
                                               "translate": [1, 2, 3]}}})
    return doc


def axis_angle_matrix(axis, degrees):
    """3 by 3 rotation by `degrees` about `axis` (the test's own oracle: Rodrigues' formula)."""
    x, y, z = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    cross = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    angle = np.radians(degrees)
    return np.eye(3) + np.sin(angle) * cross + (1.0 - np.cos(angle)) * (cross @ cross)


def load_document(tube_set, doc, name="shot.json"):
    """Write `doc` beside the tube meshes and load it."""
    return constraints.load(write_constraints(tube_set["rest"].parent / name, doc))


def test_full_document_loads_and_resolves(tube_set, document):
    loaded = load_document(tube_set, document)
    assert loaded.feature_space == "linear" and loaded.fps == 30
    assert loaded.solver_options() == {"feature_space": "linear"}
    assert [f.name for f in loaded.frames] == ["0001", "0002", "rigid", "0004"]
    rest = tube_set["vertices"]
    resolved = constraints.resolve(loaded, rest)
    ring = resolved.groups["ring"]
    assert len(ring) > 0 and np.all(np.linalg.norm(rest[ring] - [0, 0, 2.4], axis=1) <= 0.6)
    np.testing.assert_array_equal(resolved.handles, np.concatenate([tube_set["bottom"], tube_set["top"], ring]))
    assert resolved.targets.shape == (4, len(resolved.handles), 3)
    top = slice(len(tube_set["bottom"]), len(tube_set["bottom"]) + len(tube_set["top"]))
    ring_rows = slice(top.stop, None)
    # bottom never named: rest positions in every frame
    np.testing.assert_allclose(resolved.targets[:, :top.start], np.broadcast_to(rest[tube_set["bottom"]], (4, top.start, 3)))
    # ring: rest positions until frame "rigid", which rotates it 90 degrees about z through its centroid
    np.testing.assert_allclose(resolved.targets[0, ring_rows], rest[ring])
    centroid = rest[ring].mean(axis=0)
    expected = (rest[ring] - centroid) @ axis_angle_matrix([0, 0, 1], 90).T + centroid
    np.testing.assert_allclose(resolved.targets[2, ring_rows], expected, atol=1e-12)
    # top: frame 2 positions, then translated rest positions, then the matrix
    np.testing.assert_allclose(resolved.targets[1, top], bend(rest, 80.0)[tube_set["top"]])
    np.testing.assert_allclose(resolved.targets[2, top], rest[tube_set["top"]] + [0, 0, 1])
    np.testing.assert_allclose(resolved.targets[3, top], rest[tube_set["top"]] + [0.5, 0, 0])
    # rotate about an explicit centre, then translate
    flipped = rest[ring] * [1, -1, -1] + [1, 2, 3]
    np.testing.assert_allclose(resolved.targets[3, ring_rows], flipped, atol=1e-12)


def test_readme_example_is_valid(tmp_path, tube_set):
    """The full example of pipeline/README.md loads (with stand-in mesh files at its paths)."""
    readme = (pathlib.Path(__file__).resolve().parents[2] / "pipeline" / "README.md").read_text()
    example = readme.split("A full example:")[1].split("```json")[1].split("```")[0]
    (tmp_path / "horse").mkdir()
    for name in ("reference", "1", "2", "3"):
        (tmp_path / "horse" / f"{name}.obj").write_bytes(tube_set["rest"].read_bytes())
    loaded = constraints.loads(example, tmp_path / "shot.json")
    assert list(loaded.handles) == ["head", "tail", "hooves"] and len(loaded.frames) == 4
    assert loaded.fps == 24 and loaded.solver_options()["max_iterations"] == 30


def test_underscore_members_are_notes(tube_set, document):
    document["_comment"] = "shot 12, take 3"
    document["handles"]["_spare"] = "anything"
    document["frames"][0]["targets"]["_why"] = {"any": "thing"}
    document["frames"][0]["_note"] = 1
    assert list(load_document(tube_set, document).handles) == ["bottom", "top", "ring"]
    document["handles"] = {"_only": [1]}
    with pytest.raises(ConstraintError, match="handles: expected at least one handle group"):
        load_document(tube_set, document)


def test_missing_group_keeps_previous_targets(tube_set, document):
    document["frames"][1]["targets"] = {}
    resolved = constraints.resolve(load_document(tube_set, document), tube_set["vertices"])
    np.testing.assert_array_equal(resolved.targets[1], resolved.targets[0])


def test_examples_glob_sorts_numerically_and_skips_rest(tube_set, document):
    folder = tube_set["rest"].parent
    for number in (10, 3):
        (folder / f"example_{number}.obj").write_bytes(tube_set["examples"][0].read_bytes())
    document["examples"] = "*.obj"
    loaded = load_document(tube_set, document)
    assert [p.name for p in loaded.examples] == ["example_1.obj", "example_2.obj", "example_3.obj", "example_10.obj"]
    for number in (10, 3):
        (folder / f"example_{number}.obj").unlink()


def _set(path, value):
    """A mutation that sets document[path...] = value (path: keys and indices)."""
    def mutate(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return mutate


def _delete(path):
    """A mutation that deletes document[path...]."""
    def mutate(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]
    return mutate


SCHEMA_ERRORS = [
    (_set(["format"], "other"), 'format: expected "meshik-constraints", got "other"'),
    (_set(["version"], 2), "version: version 2 is not supported"),
    (_set(["version"], "1"), 'version: expected an integer version, got "1"'),
    (_delete(["rest"]), 'top level: missing member "rest"'),
    (_set(["rest"], "missing.obj"), "rest: mesh file not found"),
    (_set(["examples"], []), "examples: expected a non-empty list"),
    (_set(["examples"], ["example_1.obj", 3]), "examples[1]: expected a string, got the number 3"),
    (_set(["examples"], "nothing*.obj"), 'examples: glob "nothing*.obj" matches no mesh file'),
    (_set(["feature_space"], "curved"), 'feature_space: expected "nonlinear" or "linear", got "curved"'),
    (_set(["fps"], 0), "fps: expected a number > 0, got 0"),
    (_set(["max_iterations"], 2.5), "max_iterations: expected an integer, got the number 2.5"),
    (_set(["colour"], "red"), "colour: unknown member"),
    (_set(["handles"], {}), "handles: expected at least one handle group"),
    (_set(["handles", "top"], [30, -2]), "handles.top[1]: expected a vertex index >= 0, got -2"),
    (_set(["handles", "top"], [30, 1.5]), "handles.top[1]: expected a vertex index, got the number 1.5"),
    (_set(["handles", "top"], [0, 7]), 'handles.top[0]: vertex 0 is already a handle in handle group "bottom"'),
    (_set(["handles", "top"], {"near": [0, 0], "radius": 1}), "handles.top.near: expected 3 numbers, got a list of 2"),
    (_set(["handles", "top"], {"near": [0, 0, 0], "radius": -1}), "handles.top.radius: expected a number > 0"),
    (_set(["handles", "top"], "head"), "handles.top: expected a list of vertex indices or a region"),
    (_set(["handles", "left foot"], [True]), 'handles["left foot"][0]: expected a vertex index, got true'),
    (_set(["frames"], []), "frames: expected a non-empty list"),
    (_set(["frames", 1], 5), "frames[1]: expected an object, got the number 5"),
    (_set(["frames", 1, "name"], "0001"), 'frames[1].name: "0001" is also the name of frames[0]'),
    (_set(["frames", 1, "name"], "../up"), 'frames[1].name: "../up" cannot be a file name'),
    (_set(["frames", 1, "targets", "neck"], []), 'frames[1].targets.neck: no handle group named "neck"'),
    (_set(["frames", 1, "targets", "top"], [[0, 0, 0]]), "frames[1].targets.top: expected 6 positions (one per handle vertex), got 1"),
    (_set(["frames", 1, "targets", "top", 2], [0, 0]), "frames[1].targets.top[2]: expected 3 numbers, got a list of 2"),
    (_set(["frames", 1, "targets", "top", 2, 1], "x"), 'frames[1].targets.top[2][1]: expected a number, got "x"'),
    # NaN and Infinity are not JSON (RFC 8259): refused as syntax errors, with their line and column.
    (_set(["frames", 1, "targets", "top", 2, 1], math.nan), "not valid JSON: line 89 column 7: syntax error while parsing value - invalid literal"),
    (_set(["frames", 1, "targets", "top", 2, 1], math.inf), "not valid JSON: line 89 column 7: syntax error while parsing value - invalid literal"),
    (_set(["handles", "top"], [2 ** 70] + list(range(31, 36))), f"handles.top[0]: expected a vertex index, got {2 ** 70}, which is too large"),
    (_set(["handles", "top"], [30, 30, 31, 32, 33, 34]),
     "handles.top[1]: vertex 30 is already a handle earlier in this group"),
    (_set(["frames", 1, "targets", "top"], {"spin": 1}), "frames[1].targets.top.spin: unknown member"),
    (_set(["frames", 1, "targets", "top"], {}), 'frames[1].targets.top: expected "translate", "rotate" or "matrix"'),
    (_set(["frames", 1, "targets", "top"], {"rotate": {"axis": [0, 0, 0], "degrees": 5}}),
     "frames[1].targets.top.rotate.axis: the rotation axis must have a non-zero, finite length"),
    (_set(["frames", 1, "targets", "top"], {"rotate": {"axis": [0, 0, 1]}}), 'frames[1].targets.top.rotate: missing member "degrees"'),
    (_set(["frames", 1, "targets", "top"], {"matrix": [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}),
     "frames[1].targets.top.matrix: not a rigid motion"),
    (_set(["frames", 1, "targets", "top"], {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}),
     "frames[1].targets.top.matrix[3]: expected the last row [0, 0, 0, 1]"),
    (_set(["frames", 1, "targets", "top"], {"matrix": [[1, 0, 0, 0]] * 3}),
     "frames[1].targets.top.matrix: expected 4 rows of 4 numbers, got a list of 3"),
    (_set(["frames", 1, "targets", "top"], {"matrix": np.eye(4).tolist(), "translate": [0, 0, 0]}),
     'frames[1].targets.top: "matrix" cannot be combined with "translate" or "rotate"'),
]


@pytest.mark.parametrize("mutate, message", SCHEMA_ERRORS, ids=[m for _, m in SCHEMA_ERRORS])
def test_schema_violation_names_the_json_path(tube_set, document, mutate, message):
    mutate(document)
    with pytest.raises(ConstraintError) as raised:
        load_document(tube_set, document)
    assert str(raised.value).startswith(str(tube_set["rest"].parent / "shot.json") + ": ")
    assert message in str(raised.value)


RESOLVE_ERRORS = [
    (_set(["handles", "top"], list(range(1000, 1006))), "handles.top[0]: vertex 1000 is out of range (the rest mesh has 36 vertices)"),
    (_set(["handles", "ring"], {"near": [9, 9, 9], "radius": 0.1}), "handles.ring: no rest vertex within radius 0.1 of [9, 9, 9]"),
    (_set(["handles", "ring"], {"near": [0, 0, 0], "radius": 0.6}), 'handles.ring: vertex 0 is also in handle group "bottom"'),
    (_set(["frames", 2, "targets", "ring"], [[0, 0, 0]]), "frames[2].targets.ring: expected 6 positions (one per handle vertex), got 1"),
]


@pytest.mark.parametrize("mutate, message", RESOLVE_ERRORS, ids=[m for _, m in RESOLVE_ERRORS])
def test_resolve_errors_name_the_json_path(tube_set, document, mutate, message):
    mutate(document)
    loaded = load_document(tube_set, document)
    with pytest.raises(ConstraintError, match="shot.json: ") as raised:
        constraints.resolve(loaded, tube_set["vertices"])
    assert message in str(raised.value)


@pytest.mark.parametrize("text, message", [
    ("{", "not valid JSON: line 1 column 2"),
    ("[1, 2]", "top level: expected an object, got a list of 2"),
    ("[" * 100000 + "]" * 100000, "JSON nested too deeply"),
])
def test_unparseable_text(tmp_path, text, message):
    path = tmp_path / "bad.json"
    path.write_text(text)
    with pytest.raises(ConstraintError, match=message):
        constraints.load(path)


def test_missing_and_binary_files(tmp_path):
    with pytest.raises(ConstraintError, match="constraint file not found"):
        constraints.load(tmp_path / "none.json")
    (tmp_path / "binary.json").write_bytes(b"\xff\xfe\x00")
    with pytest.raises(ConstraintError, match="not UTF-8 text"):
        constraints.load(tmp_path / "binary.json")


# ---- fuzzing: the loader raises ConstraintError or returns, whatever the input --------------------

JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers(min_value=-2**70, max_value=2**70)
    | st.floats(allow_nan=True, allow_infinity=True) | st.text(max_size=12),
    lambda children: st.lists(children, max_size=5) | st.dictionaries(st.text(max_size=8), children, max_size=5),
    max_leaves=25)


def _subtree_paths(node, prefix=()):
    """Every path (tuple of keys / indices) to a member of a JSON document."""
    yield prefix
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, child in items:
        yield from _subtree_paths(child, prefix + (key,))


def _loads_or_constraint_error(text, source, rest):
    """Load and resolve; any exception but ConstraintError fails the test."""
    try:
        loaded = constraints.loads(text, source)
        constraints.resolve(loaded, rest)
    except ConstraintError:
        pass


FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@FUZZ
@given(value=JSON_VALUES)
def test_fuzz_arbitrary_json(tube_set, value):
    _loads_or_constraint_error(json.dumps(value), tube_set["rest"].parent / "fuzz.json", tube_set["vertices"])


@FUZZ
@given(data=st.data())
def test_fuzz_mutated_valid_document(tube_set, document, data):
    mutated = copy.deepcopy(document)
    paths = [p for p in _subtree_paths(mutated) if p]
    for _ in range(data.draw(st.integers(1, 3))):
        path = data.draw(st.sampled_from(paths))
        node = mutated
        try:
            for key in path[:-1]:
                node = node[key]
            node[path[-1]] = data.draw(JSON_VALUES)
        except (KeyError, IndexError, TypeError):
            continue  # an earlier mutation removed this path
    _loads_or_constraint_error(json.dumps(mutated), tube_set["rest"].parent / "fuzz.json", tube_set["vertices"])


@FUZZ
@given(raw=st.binary(max_size=200))
def test_fuzz_raw_bytes(tmp_path, raw):
    path = tmp_path / "raw.json"
    path.write_bytes(raw)
    try:
        constraints.load(path)
    except ConstraintError:
        pass


# ---- the library's own behaviour through the Python API ----------------------------------------

def test_duplicate_keys_are_refused_with_their_path(tube_set):
    text = json.dumps(tube_constraints(tube_set, frames=1), indent=1).replace('"top": [', '"bottom": [', 1)
    with pytest.raises(ConstraintError, match=r"shot.json: handles.bottom: duplicate key$"):
        constraints.loads(text, tube_set["rest"].parent / "shot.json")


def test_validate_lists_every_problem(tube_set, document):
    document["fps"] = -1
    document["handles"]["top"] = [0, 31]
    document["frames"][0]["name"] = "a b"
    path = write_constraints(tube_set["rest"].parent / "many.json", document)
    assert [problem.split(": ", 2)[1] for problem in constraints.validate(path)] == [
        "handles.top[0]", "frames[0].name", "fps"]
    assert all(problem.startswith(f"{path}: ") for problem in constraints.validate(path))
    assert constraints.validate(write_constraints(tube_set["rest"].parent / "good.json", tube_constraints(tube_set, frames=1))) == []


def test_written_file_reads_back_to_the_same_targets(tube_set):
    rest = tube_set["vertices"]
    groups = {"bottom": (np.array(tube_set["bottom"]), rest[tube_set["bottom"]]),
              "top": (np.array(tube_set["top"]), bend(rest, 33.0)[tube_set["top"]])}
    path = tube_set["rest"].parent / "saved.json"
    constraints.write(path, "rest.obj", ["example_1.obj", "example_2.obj"], groups, frame_name="pose")
    resolved = constraints.resolve(constraints.load(path), rest)
    assert resolved.frame_names == ("pose",)
    np.testing.assert_array_equal(resolved.handles, np.concatenate([tube_set["bottom"], tube_set["top"]]))
    np.testing.assert_array_equal(resolved.targets[0], np.concatenate([groups["bottom"][1], groups["top"][1]]))  # exact
    with pytest.raises(ConstraintError, match='saved.json: handle group "top": the target of vertex 30 is not finite'):
        constraints.write(path, "rest.obj", ["example_1.obj"], {"top": ([30], [[0.0, np.nan, 0.0]])})
    assert constraints.resolve(constraints.load(path), rest).frame_names == ("pose",)  # the old file is kept
