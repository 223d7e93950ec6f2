"""Malformed or unusual mesh files give one-line errors naming the file; a reader crash is contained.

Issue 12, defect 4 (an OBJ or OFF face index out of range crashed MeshLab's reader, and with it the
CLI or the batch worker) and the file-kind half of defect 7 (folders, FIFOs, devices)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from meshik.errors import MeshFileError
from meshik.inputs.meshio import load_mesh

CRASHING = {
    "index.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3000\n",
    "index.off": "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3000\n",
}
REFUSED = {
    "index.ply": "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3000\n",
    "empty.stl": "solid x\nendsolid\n",
    "garbage.obj": "\x00\x01\x02 not a mesh",
    "no_faces.obj": "v 0 0 0\nv 1 0 0\n",
}


@pytest.mark.parametrize("name", sorted(CRASHING) + sorted(REFUSED))
def test_a_malformed_mesh_is_one_error_naming_the_file(tmp_path, name):
    path = tmp_path / name
    path.write_text({**CRASHING, **REFUSED}[name])
    with pytest.raises(MeshFileError) as caught:
        load_mesh(path)
    assert str(path) in str(caught.value) and "\n" not in str(caught.value)


def test_a_reader_that_dies_is_reported_as_a_malformed_file(tmp_path, monkeypatch):
    """The reader's out-of-range read crashes only sometimes: make the child die for certain."""
    import signal

    from meshik.inputs import isolated_load

    monkeypatch.setattr(isolated_load, "_read_with_pymeshlab", lambda pymeshlab, path: os.kill(os.getpid(), signal.SIGSEGV))
    path = tmp_path / "rest.obj"
    path.write_text(CRASHING["index.obj"])
    with pytest.raises(MeshFileError, match=r"rest.obj: the mesh reader crashed \(SIGSEGV\)"):
        load_mesh(path)


def test_folders_fifos_and_devices_are_not_read(tmp_path):
    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    for path, words in ((tmp_path, "is a folder"), (fifo, "not a regular file"), ("/dev/zero", "not a regular file"),
                        (tmp_path / "missing.obj", "not found")):
        with pytest.raises(MeshFileError, match=words):
            load_mesh(path)


def test_the_cli_reports_a_crashing_reader_in_one_line(tmp_path):
    path = tmp_path / "index.obj"
    path.write_text(CRASHING["index.obj"])
    command = Path(sys.executable).parent / "meshik"
    done = subprocess.run([str(command), "info", str(path)], capture_output=True, text=True)
    assert done.returncode == 1, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("meshik: error:") and str(path) in lines[0], done.stderr
