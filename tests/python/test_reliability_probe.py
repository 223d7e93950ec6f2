"""A new user's hostile probe of the CLI: every bad input or fault is one line, nothing is lost.

Issue 12: each case below runs the real `meshik` command line (in-process, `meshik.cli.main`) on a
copy of the bar sample with one thing broken, and checks the guarantees of pipeline/README.md
("Untrusted input"): exit status 1 (2 for a command-line mistake), one line on stderr that starts
with "meshik" and names the file, option or element at fault, no traceback, no input changed or
deleted, and nothing written (the output folder is not created, nothing appears beside it)."""
import hashlib
import json
import os
import shutil
from pathlib import Path

import pytest

from meshik.cli import main

SAMPLE = Path(__file__).resolve().parents[2] / "sample_meshes" / "bar"


def constraint_case(change, expected):
    """A case that edits the bar's constraint document with change(document)."""
    return {"document": change, "expected": expected}


def _set(key, value):
    def change(document):
        document[key] = value
    return change


def _drop(key):
    def change(document):
        document.pop(key)
    return change


def _frame(index, targets=None, name=None):
    def change(document):
        if targets is not None:
            document["frames"][index]["targets"] = targets
        if name is not None:
            document["frames"][index]["name"] = name
    return change


def _handles(value):
    def change(document):
        document["handles"]["base"] = value
    return change


CONSTRAINT_CASES = {
    "format missing": constraint_case(_drop("format"), "format"),
    "format wrong": constraint_case(_set("format", "gltf"), "format"),
    "version 2": constraint_case(_set("version", 2), "version"),
    "version string": constraint_case(_set("version", "1"), "version"),
    "rest missing": constraint_case(_drop("rest"), "rest"),
    "rest not found": constraint_case(_set("rest", "nothing.obj"), "nothing.obj"),
    "rest a folder": constraint_case(_set("rest", "."), "rest"),
    "rest /dev/zero": constraint_case(_set("rest", "/dev/zero"), "/dev/zero"),
    "rest a number": constraint_case(_set("rest", 3), "rest"),
    "examples empty": constraint_case(_set("examples", []), "examples"),
    "examples glob matches nothing": constraint_case(_set("examples", "none_*.obj"), "none_*.obj"),
    "examples not a list": constraint_case(_set("examples", {"a": 1}), "examples"),
    "example missing": constraint_case(_set("examples", ["example_1.obj", "gone.obj"]), "gone.obj"),
    "feature space unknown": constraint_case(_set("feature_space", "quaternion"), "feature_space"),
    "regularization negative": constraint_case(_set("weight_regularization", -1), "weight_regularization"),
    "regularization string": constraint_case(_set("weight_regularization", "0"), "weight_regularization"),
    "max_iterations 0": constraint_case(_set("max_iterations", 0), "max_iterations"),
    "max_iterations 2**31": constraint_case(_set("max_iterations", 2 ** 31), "max_iterations"),
    "max_iterations 2**70": constraint_case(_set("max_iterations", 2 ** 70), "max_iterations"),
    "max_iterations float": constraint_case(_set("max_iterations", 2.5), "max_iterations"),
    "tolerance 0": constraint_case(_set("tolerance", 0), "tolerance"),
    "fps negative": constraint_case(_set("fps", -24), "fps"),
    "fps huge": constraint_case(_set("fps", 1e308 * 10 if False else "fast"), "fps"),
    "unknown member": constraint_case(_set("handels", {}), "handels"),
    "handles missing": constraint_case(_drop("handles"), "handles"),
    "handles empty": constraint_case(_set("handles", {}), "handles"),
    "handle index negative": constraint_case(_handles([-1, 2]), "handles.base"),
    "handle index out of range": constraint_case(_handles([0, 100000]), "100000"),
    "handle index 2**63": constraint_case(_handles([0, 2 ** 63]), "handles.base"),
    "handle index float": constraint_case(_handles([0, 1.5]), "handles.base"),
    "handle group empty": constraint_case(_handles([]), "handles.base"),
    "handle repeated": constraint_case(_handles([0, 0]), "handles.base"),
    "region negative radius": constraint_case(_handles({"near": [0, 0, 0], "radius": -1}), "radius"),
    "region matches nothing": constraint_case(_handles({"near": [1e6, 0, 0], "radius": 1e-9}), "handles.base"),
    "region centre 2D": constraint_case(_handles({"near": [0, 0], "radius": 1}), "near"),
    "groups overlap": constraint_case(lambda d: d["handles"].update(tip=d["handles"]["base"][:2]), "handles"),
    "frames missing": constraint_case(_drop("frames"), "frames"),
    "frames empty": constraint_case(_set("frames", []), "frames"),
    "frame name ..": constraint_case(_frame(0, name=".."), "frames[0].name"),
    "frame name with slash": constraint_case(_frame(0, name="../../escape"), "frames[0].name"),
    "frame name empty": constraint_case(_frame(0, name=""), "frames[0].name"),
    "frame names repeat": constraint_case(_frame(1, name="0000"), "0000"),
    "frame unknown group": constraint_case(_frame(0, {"nose": {"translate": [0, 0, 0]}}), "nose"),
    "translate 2D": constraint_case(_frame(0, {"tip": {"translate": [0, 1]}}), "translate"),
    "rotate zero axis": constraint_case(_frame(0, {"tip": {"rotate": {"axis": [0, 0, 0], "degrees": 3}}}), "axis"),
    "matrix not rigid": constraint_case(_frame(0, {"tip": {"matrix": [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0],
                                                                     [0, 0, 0, 1]]}}), "matrix"),
    "matrix 3 rows": constraint_case(_frame(0, {"tip": {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}}), "matrix"),
    "positions wrong count": constraint_case(_frame(0, {"tip": [[0, 0, 0]]}), "tip"),
    "target far away (grid)": constraint_case(_frame(3, {"base": {"translate": [1e6, 0, 0]},
                                                        "tip": {"translate": [1e6, 0, 0]}}), "frame 0003"),
    "target overflow": constraint_case(_frame(3, {"tip": {"translate": [1e300, 0, 0]}}), "frame 0003"),
    "targets a string": constraint_case(_frame(0, "up"), "targets"),
    "rest name with NUL": constraint_case(_set("rest", "re\u0000st.obj"), 'the file name "re\\u0000st.obj" contains a NUL'),
    "rest is the constraint file": constraint_case(_set("rest", "animation.json"), "cannot read the mesh"),
    "frame name absolute": constraint_case(_frame(0, name="/etc/passwd"), "frames[0].name"),
    "frame name with NUL": constraint_case(_frame(0, name="a\u0000b"), 'frames[0].name: "a\\u0000b" cannot be a file name'),
    "frame name 300 characters": constraint_case(_frame(0, name="x" * 300), 'x..." cannot be a file name'),
    "frame name with backslashes": constraint_case(_frame(0, name="..\\..\\x"), "frames[0].name"),
    "frame name .": constraint_case(_frame(0, name="."), "frames[0].name"),
    "fps zero": constraint_case(_set("fps", 0), "fps"),
    "tolerance negative": constraint_case(_set("tolerance", -1), "tolerance"),
    "frames an object": constraint_case(_set("frames", {"a": 1}), "frames: expected a list"),
    "frame a number": constraint_case(_set("frames", [1]), "frames[0]: expected an object"),
    "handles a list": constraint_case(_set("handles", [1, 2]), "handles: expected an object"),
    "rotate degrees a string": constraint_case(_frame(0, {"tip": {"rotate": {"axis": [0, 0, 1], "degrees": "90"}}}),
                                               "degrees"),
}

TEXT_CASES = {
    "empty file": (b"", "animation.json"),
    "not JSON": (b"hello", "line 1"),
    "truncated": (b'{"format": "meshik-constraints", "version": 1,', "line 1"),
    "NaN literal": (b'{"format": "meshik-constraints", "version": NaN}', "line 1"),
    "duplicate key": (b'{"format": "meshik-constraints", "format": "x"}', "duplicate"),
    "a list": (b"[1, 2, 3]", "animation.json"),
    "not UTF-8": (b'{"format": "meshik-\xff"}', "UTF-8"),
    "deep nesting": (b"[" * 100000 + b"]" * 100000, "animation.json"),
    "huge number": (b'{"format": "meshik-constraints", "version": 1e999}', "line 1"),
    "binary garbage": (bytes(range(256)) * 8, "animation.json"),
    "UTF-16": ('{"format": "meshik-constraints"}'.encode("utf-16"), "not UTF-8"),
    "a JSON string": (b'"hello"', "top level"),
    "trailing garbage": (b'{"format": "meshik-constraints", "version": 1} xyz', "line 1"),
    "white space only": (b"   \n\t ", "line 2"),
}

MESH_CASES = {
    "face index out of range (OBJ)": ("rest.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3000\n", "rest.obj"),
    "empty rest": ("rest.obj", "", "rest.obj"),
    "rest without triangles": ("rest.obj", "v 0 0 0\nv 1 0 0\n", "rest.obj"),
    "garbage rest": ("rest.obj", "\x00\x01 not a mesh", "rest.obj"),
    "example with fewer vertices": ("example_1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "example_1.obj"),
    "example with other triangles": ("example_2.obj", None, "example_2.obj"),
    "degenerate rest triangle": ("rest.obj", "degenerate", "triangle"),
    "rest vertex 1e300": ("rest.obj", "huge", "rest.obj: vertex 0 has the coordinates [1e+300, 0.0, 0.0], beyond"),
    "rest vertex NaN (blamed on the rest)": ("rest.obj", "nan", "rest.obj: line 2: the coordinate nan is not a finite"),
    "rest triangle f 1 1 2 (blamed on the rest)": ("rest.obj", "repeat", "rest.obj: triangle 0 could not be read"),
    "vertex with letters (read as 0 by MeshLab)": ("rest.obj", "letters", "rest.obj: line 2: vertex coordinates are not"),
    "vertex with two coordinates": ("example_1.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "example_1.obj: line 1"),
    "face with two corners": ("rest.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "rest.obj: the mesh has no triangles"),
    "negative face index beyond the start": ("rest.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9999\n", "rest.obj"),
}

ARGUMENT_CASES = {
    "--format unknown": (["--format", "fbx"], "fbx", 1),
    "--format empty": (["--format", ","], "format", 1),
    "--quantization-bits 0": (["--quantization-bits", "0"], "quantization", 2),
    "--quantization-bits 99": (["--quantization-bits", "99"], "quantization", 1),
    "--simplify -5": (["--simplify", "-5"], "simplify", 1),
    "--simplify nonsense": (["--simplify", "lots"], "simplify", 2),
    "--simplifier unknown": (["--simplifier", "magic"], "simplifier", 2),
    "--feature-space unknown": (["--feature-space", "spline"], "feature", 2),
    "--threads 0": (["--threads", "0"], "threads", 2),
    "--threads lots": (["--threads", "lots"], "threads", 2),
    "--threads 2**40": (["--threads", str(2 ** 40)], "argument --threads: expected an integer from 1 to 4096", 2),
}


def tree_state(folder: Path):
    """{relative path: sha256} of every file under `folder`."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture()
def work(tmp_path):
    """tmp_path/in: a copy of the bar sample (no "$schema", absolute paths avoided); tmp_path/out: the output."""
    shutil.copytree(SAMPLE, tmp_path / "in")
    return tmp_path


def check_refused(work, argv, expected, capsys, status=1):
    before = tree_state(work / "in")
    code = main([str(a) for a in argv])
    error = capsys.readouterr().err
    lines = [line for line in error.splitlines() if line.strip()]
    assert code == status, error
    assert "Traceback" not in error, error
    if status == 1:
        assert len(lines) == 1 and lines[0].startswith("meshik: error:"), error
    assert expected in error, error
    assert tree_state(work / "in") == before, "an input changed"
    assert sorted(p.name for p in work.iterdir()) == ["in"], "something was written"


@pytest.mark.parametrize("case", sorted(CONSTRAINT_CASES))
def test_constraint_file_faults(work, case, capsys):
    path = work / "in" / "animation.json"
    document = json.loads(path.read_text())
    document.pop("$schema", None)
    CONSTRAINT_CASES[case]["document"](document)
    path.write_text(json.dumps(document))
    check_refused(work, ["pose", path, "--out", work / "out", "--quiet"], CONSTRAINT_CASES[case]["expected"], capsys)


@pytest.mark.parametrize("case", sorted(TEXT_CASES))
def test_constraint_file_text_faults(work, case, capsys):
    path = work / "in" / "animation.json"
    text, expected = TEXT_CASES[case]
    path.write_bytes(text)
    check_refused(work, ["pose", path, "--out", work / "out", "--quiet"], expected, capsys)


def _mesh_text(work, kind):
    rest = (work / "in" / "rest.obj").read_text().splitlines()
    vertex_lines = [i for i, line in enumerate(rest) if line.startswith("v ")]
    if kind == "degenerate":  # the first triangle's corners all at the first corner's place
        faces = [line for line in rest if line.startswith("f ")]
        corners = [vertex_lines[int(c.split("/")[0]) - 1] for c in faces[0].split()[1:]]
        return "\n".join(rest[corners[0]] if i in corners[1:] else line for i, line in enumerate(rest)) + "\n"
    if kind in ("huge", "nan", "letters"):
        bad = {"huge": "v 1e300 0 0", "nan": "v nan 0 0", "letters": "v a b c"}[kind]
        return "\n".join(bad if i == vertex_lines[0] else line for i, line in enumerate(rest)) + "\n"
    if kind == "repeat":
        first_face = next(i for i, line in enumerate(rest) if line.startswith("f "))
        return "\n".join("f 1 1 2" if i == first_face else line for i, line in enumerate(rest)) + "\n"
    faces = [i for i, line in enumerate(rest) if line.startswith("f ")]  # other triangles: swap two faces' corners
    a = rest[faces[0]].split()
    rest[faces[0]] = " ".join([a[0], a[2], a[1], a[3]])
    return "\n".join(rest) + "\n"


@pytest.mark.parametrize("case", sorted(MESH_CASES))
def test_mesh_file_faults(work, case, capsys):
    name, text, expected = MESH_CASES[case]
    if text in (None, "degenerate", "huge", "nan", "letters", "repeat"):
        text = _mesh_text(work, text)
    (work / "in" / name).write_text(text)
    check_refused(work, ["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet"], expected, capsys)


@pytest.mark.parametrize("case", sorted(ARGUMENT_CASES))
def test_argument_faults(work, case, capsys):
    extra, expected, status = ARGUMENT_CASES[case]
    check_refused(work, ["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet", *extra], expected,
                  capsys, status)


@pytest.mark.parametrize("weights, expected, status", [
    ("0.5,,0.5", "--weights", 2), ("nan,1", "--weights", 2), ("inf,0", "--weights", 2), ("1", "weights", 1),
    ("1,2,3", "weights", 1), ("1e308,1e308", "finite range", 1), ("", "--weights", 2)])
def test_blend_faults(work, capsys, weights, expected, status):
    bar = work / "in"
    check_refused(work, ["blend", bar / "rest.obj", bar / "example_1.obj", bar / "example_2.obj", "--weights", weights,
                         "--out", work / "out.ply"], expected, capsys, status)


@pytest.mark.parametrize("make", ["folder", "fifo", "device", "missing", "non-UTF-8 name"])
def test_inputs_that_are_not_files(work, capsys, make):
    target = work / "in" / "shot.json"
    if make == "folder":
        target.mkdir()
    elif make == "fifo":
        os.mkfifo(target)
    elif make == "device":
        target = Path("/dev/zero")
    elif make == "non-UTF-8 name":
        target = Path(os.fsdecode(bytes(work / "in") + b"/\xff.obj"))
        shutil.copy(work / "in" / "rest.obj", target)
    for command in (["pose", target, "--out", work / "out", "--quiet"], ["info", target]):
        check_refused(work, command, "" if make == "missing" else str(target)[:8], capsys)


@pytest.mark.parametrize("out", ["a file", "under a file", "the input folder's report"])
def test_output_folders_that_cannot_be_used(work, capsys, out):
    bar = work / "in"
    if out == "the input folder's report":  # a stray report.json listing the inputs: nothing may be deleted
        listing = {p.name: p.stat().st_size for p in bar.iterdir()}
        (bar / "report.json").write_text(json.dumps({"outputs": listing}))
        before = {p.name: p.read_bytes() for p in bar.iterdir() if p.name != "report.json"}
        assert main(["pose", str(bar / "animation.json"), "--out", str(bar), "--quiet", "--format", "ply"]) == 0
        assert all((bar / name).read_bytes() == data for name, data in before.items())
        return
    destination = bar / "rest.obj" if out == "a file" else bar / "rest.obj" / "sub"
    check_refused(work, ["pose", bar / "animation.json", "--out", destination, "--quiet"], "rest.obj", capsys)
