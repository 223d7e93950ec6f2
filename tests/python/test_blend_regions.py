"""Issue 28 through the Python API and the pipeline: the free blend and spatially varying weights
(meshik.Solver(blend=..., regions=...)), the constraint file's "blend", "regions" and
"region_smoothness" (reader and schema), and `meshik pose` and `meshik batch` with --blend/--regions end to end."""
import json

import jsonschema
import numpy as np
import pytest

import meshik
from meshik.inputs import constraints
from meshik.cli import main
from meshik.errors import ConstraintError
from pipeline_meshes import tube_constraints, write_constraints, write_tube_set


@pytest.fixture(scope="module")
def tube_set(tmp_path_factory):
    """A 120-vertex tube (rest + 2 examples bent about y and about x) in a temporary folder."""
    return write_tube_set(tmp_path_factory.mktemp("regions"), rings=12, segments=10)


def solver(tube_set, **options):
    """A solver holding the bottom and top rings of the tube."""
    handles = np.array(tube_set["bottom"] + tube_set["top"])
    return meshik.Solver(tube_set["vertices"], tube_set["faces"], tube_set["example_vertices"], handles, **options), handles


@pytest.mark.parametrize("options", [dict(blend="free"), dict(regions=3), dict(regions="auto"),
                                     dict(blend="free", regions=2, region_smoothness=0.1)])
def test_each_example_is_reproduced_from_its_own_handles(tube_set, options):
    posing, handles = solver(tube_set, **options)
    regions = posing.num_regions
    per_region = 3 if options.get("blend") == "free" else 2  # the free blend holds the rest pose as example 0
    assert posing.num_weights == per_region * regions and len(posing.triangle_regions) == len(tube_set["faces"])
    assert regions == options.get("regions", 1) or (options.get("regions") == "auto" and regions >= 2)
    for example in tube_set["example_vertices"]:
        result = posing.solve(example[handles])
        assert result.weights.shape == (per_region * regions,)
        assert np.abs(result.vertices - example).max() < 1e-5


def test_free_blend_differs_from_affine_between_the_examples(tube_set):
    affine, handles = solver(tube_set)
    free, _ = solver(tube_set, blend="free")
    assert free.blend_mode == "free" and affine.blend_mode == "affine"
    targets = 0.5 * (tube_set["example_vertices"][0] + tube_set["example_vertices"][1])[handles]
    a, f = affine.solve(targets), free.solve(targets)
    assert np.abs(a.vertices - f.vertices).max() > 1e-4
    assert f.residual <= a.residual * 1.0001  # the free space contains the affine one: w_0 = 1 - sum w_i


def test_vertex_groups_give_one_region_each_and_one_for_the_rest(tube_set):
    groups = np.full(len(tube_set["vertices"]), -1)
    groups[: len(groups) // 3] = 0
    groups[-len(groups) // 3:] = 1
    posing, handles = solver(tube_set, regions=groups)
    assert posing.num_regions == 3
    example = tube_set["example_vertices"][0]
    assert np.abs(posing.solve(example[handles]).vertices - example).max() < 1e-5


@pytest.mark.parametrize("options, message", [(dict(blend="stretchy"), "blend must be"),
                                              (dict(regions=0), "regions must be"),
                                              (dict(regions="many"), "regions must be"),
                                              (dict(region_smoothness=-1.0), "region_smoothness"),
                                              (dict(regions=np.array([0, 1])), "vertex_regions has 2 entries")])
def test_bad_options_name_themselves(tube_set, options, message):
    with pytest.raises(meshik.InputError, match=message):
        solver(tube_set, **options)


def test_initial_weights_take_every_region(tube_set):
    posing, handles = solver(tube_set, regions=2)
    example = tube_set["example_vertices"][1]
    result = posing.solve(example[handles], initial_weights=np.array([0.0, 1.0, 0.0, 1.0]))
    assert np.abs(result.vertices - example).max() < 1e-5
    with pytest.raises(meshik.InputError, match="initial_weights"):
        posing.solve(example[handles], initial_weights=np.array([0.0, 1.0]))


@pytest.fixture(scope="module")
def schema():
    """The packaged schema's validator."""
    return jsonschema.Draft202012Validator(json.loads(constraints.SCHEMA_PATH.read_text()))


@pytest.mark.parametrize("settings, expected", [
    ({"blend": "free"}, {"blend": "free"}),
    ({"regions": 4, "region_smoothness": 0.5}, {"regions": 4, "region_smoothness": 0.5}),
    ({"regions": "auto"}, {"regions": "auto"}),
    ({"regions": {"front": [0, 1, 2], "back": [50, 51], "_note": "ignored"}},
     {"regions": {"front": (0, 1, 2), "back": (50, 51)}}),
])
def test_constraint_file_settings_load_and_pass_the_schema(tube_set, schema, settings, expected):
    document = dict(tube_constraints(tube_set, frames=2), **settings)
    assert list(schema.iter_errors(document)) == []
    loaded = constraints.load(write_constraints(tube_set["rest"].parent / "settings.json", document))
    assert loaded.solver_options() == expected


@pytest.mark.parametrize("settings, message", [
    ({"blend": "rigid"}, 'blend: expected "affine" or "free", got "rigid"'),
    ({"regions": 0}, "regions: expected a region count >= 1"),
    ({"regions": "some"}, 'regions: expected a count, "auto" or vertex groups'),
    ({"regions": {"a": [1, 2], "b": [2]}}, 'regions.b[0]: vertex 2 is already in region "a"'),
    ({"region_smoothness": -2}, "region_smoothness"),
])
def test_bad_constraint_settings_name_their_json_path(tube_set, schema, settings, message):
    document = dict(tube_constraints(tube_set, frames=2), **settings)
    with pytest.raises(ConstraintError) as error:
        constraints.load(write_constraints(tube_set["rest"].parent / "bad.json", document))
    assert message in str(error.value)
    if "already in region" not in message:  # a rule the schema cannot state
        assert list(schema.iter_errors(document))


def test_vertex_group_out_of_range_names_the_group(tube_set):
    with pytest.raises(ConstraintError, match=r"regions.front: vertex 9999 is out of range"):
        constraints.region_vertex_groups({"front": [0, 9999]}, 120, "shot.json")


@pytest.mark.parametrize("file_settings, flags", [({"blend": "free", "regions": {"low": list(range(40))}}, []),
                                                  ({}, ["--blend", "free", "--regions", "2"])])
def test_meshik_pose_uses_the_settings(tube_set, tmp_path, file_settings, flags):
    document = dict(tube_constraints(tube_set, frames=3), **file_settings)
    path = write_constraints(tube_set["rest"].parent / f"pose_{len(flags)}.json", document)
    out = tmp_path / "out"
    assert main(["pose", str(path), "--out", str(out), "--format", "ply", "--quiet"] + flags) == 0
    report = json.loads((out / "report.json").read_text())
    assert report["solver"]["blend"] == "free"
    assert report["solver"]["regions"] == (2 if flags else {"low": list(range(40))})


def test_meshik_batch_settings_apply_where_the_file_sets_none(tube_set, tmp_path):
    """`meshik batch --blend/--regions`: the jobs whose file says nothing take them; a file's own settings stay."""
    folder = tube_set["rest"].parent
    says = write_constraints(folder / "batch_says.json",
                             dict(tube_constraints(tube_set, frames=2), blend="affine", regions={"low": list(range(40))}))
    silent = write_constraints(folder / "batch_silent.json", tube_constraints(tube_set, frames=2))
    out = tmp_path / "out"
    assert main(["batch", str(says), str(silent), "--out", str(out), "--jobs", "1", "--format", "ply", "--quiet",
                 "--blend", "free", "--regions", "2"]) == 0
    solver_of = {name: json.loads((out / name / "report.json").read_text())["solver"] for name in ("batch_says", "batch_silent")}
    assert (solver_of["batch_says"]["blend"], solver_of["batch_says"]["regions"]) == ("affine", {"low": list(range(40))})
    assert (solver_of["batch_silent"]["blend"], solver_of["batch_silent"]["regions"]) == ("free", 2)
