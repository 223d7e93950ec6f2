"""Hostile mesh files through every reader MeshLab has (issue 23): `meshik info` and `meshik pose`.

Families:
- reader formats: every extension pymeshlab reads, each as an empty file, 100 zero bytes, random
  bytes and text garbage. Seen before the fix: an empty .vmi never finishes, an empty .asc dies of
  SIGFPE, an empty .fbx of SIGSEGV, 100 zero bytes as .stl loop for ever. Each is one line, within
  the reader's time limit (MESHIK_READER_SECONDS=4 here), and no reader child is left.
- non-finite coordinates in every text and binary format the values check reads (OBJ, OFF, ASCII
  and binary PLY, ASCII and binary STL): refused naming the line or vertex (MeshLab drops the
  vertex and shifts every later index).
- the issue's own files: a truncated binary STL, ASCII STL garbage, a PLY face list count of
  0xFFFFFFF0, a 20-digit OBJ face index, `v nan nan nan` on the same line of the rest and every
  example, an example scaled by 1e38 and a vertex at 1e300.
The readers run in a forked child, so these run in-process (meshik.cli.main), in parallel with nothing.
"""
import os
import shutil
import struct

import numpy as np
import pytest

from hostile_checks import assert_refused, run_in_process, tree_state
from meshik.inputs.isolated_load import READ_SECONDS_VARIABLE

READER_FORMATS = ("ply", "stl", "obj", "qobj", "off", "ptx", "vmi", "asc", "3ds", "3mf", "bre", "dae", "ctm", "e57",
                  "apts", "xyz", "pts", "gltf", "pdb", "tri", "x3d", "wrl", "fbx")
CONTENTS = {
    "empty": b"",
    "100 zero bytes": bytes(100),
    "random bytes": np.random.default_rng(23).integers(0, 256, 4096, dtype=np.uint8).tobytes(),
    "text garbage": b"hello mesh\n" * 40,
}
NON_FINITE = ("nan", "-inf", "inf", "1e999", "NaN")
LIMIT_SECONDS = 4


@pytest.fixture(autouse=True)
def short_reader_limit(monkeypatch):
    """The reader child's time limit: 4 s (and the per-MB allowance of these small files)."""
    monkeypatch.setenv(READ_SECONDS_VARIABLE, str(LIMIT_SECONDS))


@pytest.fixture()
def work(tmp_path, samples_dir):
    """tmp_path/in: a copy of the bar sample."""
    shutil.copytree(samples_dir / "bar", tmp_path / "in")
    return tmp_path


def refuse_info(work, path, capsys, expected=None):
    """`meshik info path` is refused with the guarantees, naming `expected` (default: the file)."""
    before = tree_state(work / "in")
    outcome = run_in_process(["info", path], capsys)
    assert_refused(outcome, str(path) if expected is None else expected, work / "in", before, work, ("in",))
    assert outcome.seconds < LIMIT_SECONDS + 10, outcome.seconds
    return outcome


@pytest.mark.parametrize("content", sorted(CONTENTS))
@pytest.mark.parametrize("extension", READER_FORMATS)
def test_every_reader_on_hostile_bytes(work, capsys, extension, content):
    path = work / "in" / f"hostile.{extension}"
    path.write_bytes(CONTENTS[content])
    refuse_info(work, path, capsys)


def _bar_rest(work):
    """(#V by 3 float positions, #F by 3 zero-based triangles) of the bar's rest mesh, read as text."""
    lines = (work / "in" / "rest.obj").read_text().splitlines()
    vertices = np.array([[float(x) for x in line.split()[1:4]] for line in lines if line.startswith("v ")])
    faces = np.array([[int(c.split("/")[0]) - 1 for c in line.split()[1:4]] for line in lines if line.startswith("f ")])
    return vertices, faces


def _write(path, vertices, faces, bad):
    """Write the mesh in the format of path's extension (".obj", ".off", ".ply" ASCII, ".bply" binary
    PLY, ".stl" ASCII, ".bstl" binary STL) with vertex 5's x coordinate replaced by `bad`."""
    kind = path.suffix
    text = [f"{x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    text[5] = f"{bad} " + text[5].split(" ", 1)[1]
    if kind == ".obj":
        body = "".join(f"v {t}\n" for t in text) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)
    elif kind == ".off":
        body = f"OFF\n{len(vertices)} {len(faces)} 0\n" + "".join(f"{t}\n" for t in text) + \
            "".join(f"3 {a} {b} {c}\n" for a, b, c in faces)
    elif kind == ".ply":
        body = (f"ply\nformat ascii 1.0\nelement vertex {len(vertices)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
                + "".join(f"{t}\n" for t in text) + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces))
    elif kind == ".stl":
        corners = [text[i] for tri in faces for i in tri]
        body = "solid bar\n" + "".join(
            "facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {c}\n" for c in corners[3 * k:3 * k + 3])
            + "endloop\nendfacet\n" for k in range(len(faces))) + "endsolid bar\n"
    else:
        values = vertices.astype(np.float32).copy()
        values[5, 0] = np.float32(float(bad))
        if kind == ".bply":
            header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\nproperty float x\n"
                      f"property float y\nproperty float z\nelement face {len(faces)}\n"
                      f"property list uchar int vertex_indices\nend_header\n").encode()
            face_bytes = b"".join(struct.pack("<B3i", 3, *map(int, tri)) for tri in faces)
            path.with_suffix(".ply").write_bytes(header + values.tobytes() + face_bytes)
            return path.with_suffix(".ply")
        records = b"".join(struct.pack("<3f", 0, 0, 1) + values[list(tri)].tobytes() + b"\0\0" for tri in faces)
        path.with_suffix(".stl").write_bytes(bytes(80) + struct.pack("<I", len(faces)) + records)
        return path.with_suffix(".stl")
    path.write_text(body)
    return path


@pytest.mark.parametrize("bad", NON_FINITE)
@pytest.mark.parametrize("kind", [".obj", ".off", ".ply", ".bply", ".stl", ".bstl"])
def test_non_finite_coordinates_in_every_checked_format(work, capsys, kind, bad):
    vertices, faces = _bar_rest(work)
    path = _write(work / "in" / f"values{kind}", vertices, faces, bad)
    outcome = refuse_info(work, path, capsys)
    line = outcome.stderr.strip()
    assert "not a finite number" in line and ("line " in line or "vertex 5" in line or "facet" in line), line


def test_nan_vertex_in_rest_and_every_example_is_refused_with_its_line(work, capsys):
    """The issue's case: MeshLab dropped the vertex in all three files alike, every later index shifted
    and the handles posed other vertices, exit 0."""
    for name in ("rest.obj", "example_1.obj", "example_2.obj"):
        path = work / "in" / name
        lines = path.read_text().splitlines()
        index = [i for i, line in enumerate(lines) if line.startswith("v ")][40]
        lines[index] = "v nan nan nan"
        path.write_text("\n".join(lines) + "\n")
    before = tree_state(work / "in")
    outcome = run_in_process(["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet"], capsys)
    assert_refused(outcome, f"rest.obj: line {index + 1}: the coordinate nan is not a finite number", work / "in",
                   before, work, ("in",))


SPECIAL_FILES = {
    "binary STL truncated (header: 2 facets)": ("z.stl", bytes(80) + struct.pack("<I", 2) + bytes(60), "malformed STL"),
    "ASCII STL garbage": ("g.stl", b"solid x\nfacet nonsense\n" * 20, "g.stl"),
    "STL with NUL after solid": ("n.stl", b"solid x\n" + bytes(64), "malformed STL"),
    "PLY face count 0xFFFFFFF0": ("f.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                  b"property float y\nproperty float z\nelement face 1\n"
                                  b"property list uchar int vertex_indices\nend_header\n" + bytes(36)
                                  + struct.pack("<B", 255) + struct.pack("<I", 0xFFFFFFF0), "f.ply"),
    "PLY vertex count 2**32": ("c.ply", b"ply\nformat ascii 1.0\nelement vertex 4294967296\nproperty float x\n"
                               b"end_header\n0\n", "c.ply"),
    "OBJ face index of 20 digits": ("i.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
                                    "line 4: face index 99999999999999999999 is out of range"),
    "OBJ vertex at 1e300": ("h.obj", b"v 1e300 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vertex 0 has the coordinates"),
    "OFF header only": ("o.off", b"OFF\n100000000 100000000 0\n", "o.off"),
}


@pytest.mark.parametrize("case", sorted(SPECIAL_FILES))
def test_the_issues_malformed_files(work, capsys, case):
    name, data, expected = SPECIAL_FILES[case]
    path = work / "in" / name
    path.write_bytes(data)
    outcome = refuse_info(work, path, capsys, expected)
    assert "buffer overflow" not in outcome.stderr


def test_an_example_scaled_by_1e38_is_refused_naming_it(work, capsys):
    path = work / "in" / "example_2.obj"
    lines = [f"v {' '.join(repr(float(x) * 1e38) for x in line.split()[1:4])}" if line.startswith("v ") else line
             for line in path.read_text().splitlines()]
    path.write_text("\n".join(lines) + "\n")
    before = tree_state(work / "in")
    outcome = run_in_process(["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet"], capsys)
    assert_refused(outcome, "example_2.obj: vertex", work / "in", before, work, ("in",))


def test_a_fifo_as_the_rest_mesh_is_named_as_such(work, capsys):
    (work / "in" / "rest.obj").unlink()
    os.mkfifo(work / "in" / "rest.obj")
    outcome = run_in_process(["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet"], capsys)
    assert_refused(outcome, "is not a regular file (a device, FIFO or socket)", work=work, allowed=("in",))
