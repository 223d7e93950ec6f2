"""Finite but huge inputs are refused with a message naming the frame and handle, never written.

Issue 12, defect 3: a solve that leaves the finite range is an error, not "converged"; a blend with
huge weights writes nothing; one far-off frame cannot blur a whole animation's shared Draco grid."""
import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import meshik
from meshik.errors import PipelineError
from meshik.inputs.meshio import load_example_set
from meshik.pipeline import pose_job

MESHIK = Path(sys.executable).parent / "meshik"


@pytest.fixture()
def bar(samples_dir, tmp_path):
    folder = tmp_path / "bar"
    shutil.copytree(samples_dir / "bar", folder)
    return folder


@pytest.mark.parametrize("scale", [1e300, 1e150, 1e30])
def test_a_solve_that_overflows_raises_naming_the_handle(bar, scale):
    meshes = load_example_set(bar / "rest.obj", [bar / "example_1.obj", bar / "example_2.obj"])
    solver = meshik.Solver(meshes.rest, meshes.faces, list(meshes.examples), handles=[0, 1, 130])
    with pytest.raises(meshik.InputError, match=r"finite range.*handle vertex 130"):
        solver.solve(meshes.rest[[0, 1, 130]] * scale)
    assert np.isfinite(solver.solve(meshes.rest[[0, 1, 130]]).vertices).all()  # the solver still works


def test_a_blend_with_huge_weights_writes_nothing(bar, tmp_path):
    out = tmp_path / "blend.ply"
    done = subprocess.run([str(MESHIK), "blend", str(bar / "rest.obj"), str(bar / "example_1.obj"),
                           str(bar / "example_2.obj"), "--weights", "1e308,1e308", "--out", str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 1 and done.stderr.startswith("meshik: error:") and "finite range" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["bar"]


def far_frame(bar, translate):
    document = json.loads((bar / "animation.json").read_text())
    document["frames"][3]["targets"] = {"base": {"translate": [translate, 0, 0]}, "tip": {"translate": [translate, 0, 0]}}
    path = bar / f"far_{translate:g}.json"
    path.write_text(json.dumps(document))
    return path


@pytest.mark.parametrize("translate", [1e6, 1e30])
def test_one_far_frame_is_refused_naming_frame_and_handle(bar, tmp_path, translate):
    out = tmp_path / "out"
    with pytest.raises(PipelineError, match=r"frame 0003, handle vertex \d+: the animation spans"):
        pose_job(far_frame(bar, translate), out, quiet=True)
    assert not out.exists()


def test_a_far_frame_is_fine_where_no_shared_grid_is_written(bar, tmp_path):
    report = pose_job(far_frame(bar, 1e6), tmp_path / "out", formats="ply", quiet=True)
    assert report["outputs"] and np.isfinite([f["residual"] for f in report["frames"]]).all()
