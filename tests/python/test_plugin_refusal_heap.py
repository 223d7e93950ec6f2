"""A filter call that raises pymeshlab.PyMeshLabException, then its MeshSet freed, then a mesh loaded
into a new MeshSet: through plugin_helpers.apply_refused nothing touches the freed MeshSet.

pymeshlab 2025.7 keeps a pointer into the MeshSet of a filter call that raised and the next mesh
load (in any MeshSet) writes through it (plugin/README.md, "Known issues"). Whether that write shows
as a crash depends on the heap's layout, so the check runs the sequence under valgrind, which
reports every read or write into a freed block. Valgrind cannot run the -march=native MeshIK
modules, so the refusing filter here is a built-in one: the stale pointer is pymeshlab's, the same
for any filter that raises (the MeshIK filters' refusals go through apply_refused in the tests)."""
import pathlib
import shutil
import subprocess
import sys

import pytest

HERE = pathlib.Path(__file__).resolve().parent

CHILD = """
import gc
import sys
import pymeshlab
from plugin_helpers import apply_refused
path = sys.argv[1]
ms = pymeshlab.MeshSet()
ms.load_new_mesh(path)
apply_refused(ms, "compute_selection_by_condition_per_vertex", condselect="(q < ")
del ms
gc.collect()  # the refusal's traceback holds the MeshSet in a reference cycle
fresh = pymeshlab.MeshSet()
fresh.load_new_mesh(path)
print("loaded", fresh.current_mesh().vertex_number())
"""


def test_refused_filter_leaves_no_pointer_into_its_freed_mesh_set(samples_dir, tmp_path):
    valgrind = shutil.which("valgrind")
    if valgrind is None:
        pytest.skip("valgrind is not installed (scripts/apt-packages.txt lists it)")
    path = samples_dir / "bar" / "rest.obj"
    log = tmp_path / "valgrind.log"
    done = subprocess.run([valgrind, f"--log-file={log}", "--num-callers=16", sys.executable, "-c", CHILD, str(path)],
                          cwd=HERE, env={"PATH": "/usr/bin:/bin", "PYTHONMALLOC": "malloc"}, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    vertices = sum(1 for line in path.read_text().splitlines() if line.startswith("v "))
    assert done.stdout.splitlines()[-1] == f"loaded {vertices}"
    report = log.read_text()
    assert "free'd" not in report, report[report.find("free'd") - 4000:report.find("free'd") + 500]
