"""The forked mesh reader has a time limit and dies with its parent (issue 23).

Before: 100 zero bytes as an .stl kept MeshLab's reader looping for 12 minutes; SIGINT to the
process group made the parent exit 130 while the reader ran on at 100% CPU, ignoring SIGINT and
SIGTERM and holding the caller's stdout and stderr open. Here a large OBJ (several seconds of
reading) stands for a reader that does not finish: the child is killed at its time limit, and
whatever ends the parent (SIGINT or SIGTERM to the group, SIGKILL of the parent alone) ends the child.
"""
import os
import signal
import subprocess
import sys
import time

import numpy as np
import psutil
import pytest

from hostile_checks import CLI, session_alive
from meshik.errors import MeshFileError
from meshik.inputs.isolated_load import isolated_load


@pytest.fixture(scope="module")
def slow_obj(tmp_path_factory):
    """An OBJ of a 700 by 700 grid (490,000 vertices, about 1 million triangles): seconds to read."""
    path = tmp_path_factory.mktemp("slow") / "grid.obj"
    n = 700
    y, x = np.mgrid[0:n, 0:n]
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    corner = (y[:-1, :-1] * n + x[:-1, :-1]).ravel() + 1
    faces = np.concatenate([np.column_stack([corner, corner + 1, corner + n]),
                            np.column_stack([corner + 1, corner + n + 1, corner + n])])
    lines = [f"v {x} {y} 0\n" for x, y in vertices[:, :2].astype(int).tolist()]
    lines += [f"f {a} {b} {c}\n" for a, b, c in faces.tolist()]
    path.write_text("".join(lines))
    return path


def test_the_reader_is_killed_at_its_time_limit(slow_obj):
    earlier = {child.pid for child in psutil.Process().children(recursive=True)}  # other tests' (a resource tracker)
    start = time.monotonic()
    with pytest.raises(MeshFileError, match=r"grid.obj: the mesh reader did not finish within 0 s"):
        isolated_load(slow_obj, time_limit=0.3)
    assert time.monotonic() - start < 5
    left = [child for child in psutil.Process().children(recursive=True) if child.pid not in earlier]
    assert not left, "the reader child was left running"


@pytest.mark.parametrize("how", ["SIGINT to the group", "SIGTERM to the group", "SIGKILL to the parent alone"])
def test_the_reader_dies_with_its_parent(slow_obj, how):
    process = subprocess.Popen([sys.executable, "-c", CLI, "info", str(slow_obj)], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, start_new_session=True)
    try:
        deadline = time.monotonic() + 60
        while not psutil.Process(process.pid).children() and time.monotonic() < deadline:
            time.sleep(0.05)
        reader = psutil.Process(process.pid).children()
        assert reader, "the reader child never started"
        time.sleep(0.5)
        if how == "SIGKILL to the parent alone":
            process.kill()
        else:
            os.killpg(process.pid, signal.SIGINT if how.startswith("SIGINT") else signal.SIGTERM)
        _, error = process.communicate(timeout=20)  # returns only once the child closed stdout and stderr too
        gone, alive = psutil.wait_procs(reader, timeout=5)
        assert not alive, f"the reader outlived its parent ({how})"
        assert not session_alive(process.pid)
        if how != "SIGKILL to the parent alone":
            assert process.returncode == 130 and error.decode().strip() == "meshik: interrupted", error
    finally:
        if session_alive(process.pid):
            os.killpg(process.pid, signal.SIGKILL)
