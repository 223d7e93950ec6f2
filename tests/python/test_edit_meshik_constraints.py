"""The constraint file that the MeshLab tool "MeshIK: Drag to Pose" saves (its writer in
plugin/edit_meshik/logic, run through the test command edit_meshik_write_frame) reads back with
the pipeline's loader: same handles, bit-identical targets, same solver options."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

from meshik.inputs import constraints
from meshik.errors import ConstraintError

ROOT = pathlib.Path(__file__).resolve().parents[2]
WRITER = pathlib.Path(os.environ.get("MESHIK_BUILD_DIR", ROOT / "build")) / "tests" / "edit_meshik_write_frame"


def write_frame(out, rest, examples, handles, targets, feature_space="nonlinear", k=0.0, iterations=30):
    """Runs the tool's writer; returns the finished process (check=False)."""
    if not WRITER.is_file():
        pytest.fail(f"{WRITER} is missing (run `make build`)")
    args = [str(WRITER), str(out), str(rest), ",".join(str(e) for e in examples),
            ",".join(str(h) for h in handles), ",".join(repr(float(x)) for x in np.ravel(targets)),
            feature_space, repr(k), str(iterations)]
    return subprocess.run(args, capture_output=True, text=True)


def test_saved_frame_reads_back_with_the_pipelines_loader(samples_dir, tmp_path):
    limb = samples_dir / "limb"
    rest = np.loadtxt([l[2:] for l in (limb / "rest.obj").read_text().splitlines() if l.startswith("v ")])
    handles = [0, 7, 131, 250]
    rng = np.random.default_rng(3)
    targets = rest[handles] + rng.normal(scale=0.3, size=(len(handles), 3)) / 3.0
    examples = sorted(limb.glob("example_*.obj"))
    out = tmp_path / "drag session.json"
    done = write_frame(out, limb / "rest.obj", examples, handles, targets, "linear", 0.125, 12)
    assert done.returncode == 0, done.stderr

    loaded = constraints.load(out)
    assert loaded.rest == (limb / "rest.obj").resolve()
    assert list(loaded.examples) == [e.resolve() for e in examples]
    assert loaded.feature_space == "linear"
    assert loaded.weight_regularization == 0.125
    assert loaded.max_iterations == 12
    assert [frame.name for frame in loaded.frames] == ["drag"]
    resolved = constraints.resolve(loaded, rest)
    assert list(resolved.handles) == handles
    assert np.array_equal(resolved.targets[0], targets), "targets must read back bit for bit"


def test_a_non_finite_target_is_refused_naming_the_handle_and_nothing_is_written(samples_dir, tmp_path):
    limb = samples_dir / "limb"
    out = tmp_path / "drag.json"
    done = write_frame(out, limb / "rest.obj", [limb / "example_1.obj"], [3, 4],
                       [[0, 0, 0], [0, float("inf"), 0]])
    assert done.returncode == 1
    assert "the target of vertex 4 is not finite" in done.stderr and "drag.json" in done.stderr
    assert list(tmp_path.iterdir()) == []


def test_the_loader_reports_a_missing_mesh_of_a_saved_frame(samples_dir, tmp_path):
    limb = samples_dir / "limb"
    out = tmp_path / "drag.json"
    done = write_frame(out, tmp_path / "gone.obj", [limb / "example_1.obj"], [3], [[0, 0, 0]])
    assert done.returncode == 0, done.stderr
    with pytest.raises(ConstraintError, match="rest"):
        constraints.load(out)
