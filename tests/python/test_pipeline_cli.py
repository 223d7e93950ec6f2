"""The `meshik` command: bad input gives a clear message, a non-zero exit and no output; --help
explains every option; info and blend work on real files."""
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from meshik.cli import main
from meshik.inputs.meshio import load_mesh
from pipeline_meshes import bend, tube_constraints, write_constraints, write_obj, write_tube_set


@pytest.fixture()
def shot(tmp_path):
    """A tube example set and a valid 3-frame constraint file in tmp_path/in."""
    tube_set = write_tube_set(tmp_path / "in", rings=8, segments=6)
    document = tube_constraints(tube_set, frames=3)
    return {"set": tube_set, "document": document, "path": write_constraints(tmp_path / "in" / "shot.json", document),
            "out": tmp_path / "out"}


def run_failing(argv, capsys, message):
    """Run the CLI, expect exit status 1 and `message` in stderr."""
    status = main([str(a) for a in argv])
    error = capsys.readouterr().err
    assert status == 1, error
    assert message in error, error
    return error


def rewrite(shot, change):
    """Apply change(document) and rewrite the constraint file."""
    change(shot["document"])
    write_constraints(shot["path"], shot["document"])


BAD_INPUTS = {
    "malformed JSON": (lambda shot: shot["path"].write_text('{"format": "meshik-constraints",'), "not valid JSON: line 1"),
    "schema violation": (lambda shot: rewrite(shot, lambda d: d.update(version=7)), "version: version 7 is not supported"),
    "missing rest mesh": (lambda shot: shot["set"]["rest"].unlink(), "rest: mesh file not found"),
    "missing example": (lambda shot: shot["set"]["examples"][1].unlink(), "examples[1]: mesh file not found"),
    "different topology": (lambda shot: write_obj(shot["set"]["examples"][0], shot["set"]["vertices"],
                                                  shot["set"]["faces"][::-1]), "example_1.obj: triangle 0 is"),
    "handle out of range": (lambda shot: rewrite(shot, lambda d: d["handles"].update(bottom=[0, 1, 2, 3, 4, 480])),
                            "handles.bottom[5]: vertex 480 is out of range (the rest mesh has 48 vertices)"),
    "NaN target": (lambda shot: rewrite(shot, lambda d: d["frames"][2]["targets"]["top"][4].__setitem__(1, math.nan)),
                   "not valid JSON: line 128 column 7: syntax error while parsing value - invalid literal"),  # NaN is not JSON
}


@pytest.mark.parametrize("name", BAD_INPUTS)
def test_bad_input_fails_cleanly(shot, capsys, name):
    damage, message = BAD_INPUTS[name]
    damage(shot)
    error = run_failing(["pose", shot["path"], "--out", shot["out"]], capsys, message)
    assert error.startswith("meshik: error: ")
    assert not shot["out"].exists()  # no partial output


def test_unwritable_output_folder(shot, capsys, tmp_path):
    blocker = tmp_path / "blocker"
    blocker.write_text("a file where the output folder should go")
    run_failing(["pose", shot["path"], "--out", blocker / "job"], capsys, "cannot be created")
    assert blocker.read_text().startswith("a file")


def test_bad_options(shot, capsys):
    run_failing(["pose", shot["path"], "--out", shot["out"], "--format", "drc,xyz123"], capsys, "unknown output format 'xyz123'")
    assert main(["pose", str(shot["path"]), "--out", str(shot["out"]), "--simplify", "1.5"]) == 2
    assert main(["pose", str(shot["path"]), "--out", str(shot["out"]), "--simplifier", "magic"]) == 2
    assert "invalid choice: 'magic'" in capsys.readouterr().err
    assert not shot["out"].exists()


def test_help_explains_every_option(capsys):
    for command, options in {"pose": ["--out", "--simplify", "--simplify-first", "--simplifier", "--format", "--feature-space",
                                      "--quantization-bits", "--force", "--quiet"],
                             "batch": ["--jobs", "--out", "--quiet"], "blend": ["--weights", "--out", "--feature-space"],
                             "info": ["--json"]}.items():
        assert main([command, "--help"]) == 0
        text = capsys.readouterr().out
        for option in options:
            assert option in text, (command, option)
    assert main([]) == 2


def test_installed_command_exit_status(shot):
    """The `meshik` command beside this Python (written by scripts/setup.sh) returns the status to the shell."""
    command = pathlib.Path(sys.executable).parent / "meshik"
    if not command.exists():
        pytest.fail(f"{command} missing: run scripts/setup.sh venv")
    done = subprocess.run([str(command), "pose", str(shot["path"].parent / "missing.json"), "--out", str(shot["out"])],
                          capture_output=True, text=True)
    assert done.returncode == 1 and "constraint file not found" in done.stderr


def test_blend_reproduces_an_example(shot, tmp_path):
    out = tmp_path / "blend" / "example1.ply"
    tube_set = shot["set"]
    assert main(["blend", str(tube_set["rest"]), *map(str, tube_set["examples"]), "--weights", "1,0", "--out", str(out)]) == 0
    vertices, faces = load_mesh(out)
    np.testing.assert_allclose(vertices, tube_set["example_vertices"][0], atol=1e-6)
    np.testing.assert_array_equal(faces, tube_set["faces"])
    assert main(["blend", str(shot["path"]), "--weights", "0,0", "--out", str(tmp_path / "rest.drc")]) == 0
    assert (tmp_path / "rest.drc").stat().st_size > 0


def test_blend_weight_count_must_match(shot, capsys, tmp_path):
    run_failing(["blend", shot["path"], "--weights", "1", "--out", tmp_path / "x.ply"], capsys,
                "1 weights given for 2 examples")
    assert not (tmp_path / "x.ply").exists()


def test_info_describes_meshes_and_constraints(shot, capsys, tmp_path):
    tube_set = shot["set"]
    other = write_obj(tmp_path / "other.obj", bend(tube_set["vertices"], 10), tube_set["faces"][:, [0, 2, 1]])
    assert main(["info", "--json", str(tube_set["rest"]), str(tube_set["examples"][0]), str(other), str(shot["path"])]) == 0
    rest, example, flipped, constraints = json.loads(capsys.readouterr().out)
    assert rest["vertices"] == 48 and rest["triangles"] == 84 and rest["boundary_edges"] == 12
    assert example["same_triangles_as"] == {str(tube_set["rest"]): True}
    assert flipped["same_triangles_as"] == {str(tube_set["rest"]): False}
    assert constraints["kind"] == "constraints" and constraints["frames"] == 3 and constraints["handle_groups"] == ["bottom", "top"]
    run_failing(["info", tmp_path / "nothing.obj"], capsys, "nothing.obj: file not found")


def test_info_describes_pipeline_outputs(shot, capsys):
    assert main(["pose", str(shot["path"]), "--out", str(shot["out"]), "--quiet"]) == 0
    assert main(["info", "--json", str(shot["out"] / "frames" / "0002.drc"), str(shot["out"] / "shot.glb")]) == 0
    drc, glb = json.loads(capsys.readouterr().out)
    assert drc["kind"] == "draco" and drc["encoding"] == "edgebreaker" and drc["original_ids"] and drc["vertices"] == 48
    assert glb["kind"] == "glb animation" and glb["frames"] == 3 and glb["triangles"] == 84
    assert glb["duration_seconds"] == pytest.approx(2 / 24)
    (shot["out"] / "broken.drc").write_bytes(b"DRACO but not really")
    run_failing(["info", shot["out"] / "broken.drc"], capsys, "broken.drc: cannot decode Draco data")
