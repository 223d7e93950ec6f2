"""The checked-in sample_meshes/ are exactly what scripts/generate_samples.py produces, and each
set is a valid example set (same triangles in every pose, a constraint file naming its files)."""
import filecmp
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SETS = ["bar", "flag", "limb", "wings"]


def read_obj(path: pathlib.Path):
    """(#V by 3 float array, #F by 3 int array) from the v / f lines of an OBJ file."""
    vertices, faces = [], []
    for line in path.read_text().splitlines():
        parts = line.split()
        if parts and parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            faces.append([int(x.split("/")[0]) - 1 for x in parts[1:4]])
    return np.array(vertices), np.array(faces)


def test_generator_reproduces_checked_in_samples(tmp_path, samples_dir):
    subprocess.run([sys.executable, str(ROOT / "scripts" / "generate_samples.py"), "--out", str(tmp_path)],
                   check=True, capture_output=True)
    for name in SETS:
        generated = sorted(p.name for p in (tmp_path / name).iterdir())
        checked_in = sorted(p.name for p in (samples_dir / name).iterdir())
        assert generated == checked_in, name
        mismatch = filecmp.cmpfiles(tmp_path / name, samples_dir / name, generated, shallow=False)[1]
        assert not mismatch, f"{name}: regenerate sample_meshes (differs: {mismatch})"


@pytest.mark.parametrize("name", SETS)
def test_sample_is_a_consistent_example_set(samples_dir, name):
    folder = samples_dir / name
    constraints = json.loads((folder / "animation.json").read_text())
    assert constraints["format"] == "meshik-constraints" and constraints["version"] == 1
    rest_v, rest_f = read_obj(folder / constraints["rest"])
    assert len(constraints["examples"]) >= 2 and len(constraints["frames"]) >= 10
    for example in constraints["examples"]:
        v, f = read_obj(folder / example)
        assert v.shape == rest_v.shape and np.array_equal(f, rest_f)
        assert np.abs(v - rest_v).max() > 0.05, f"{example} is not a different pose"
    areas = np.linalg.norm(np.cross(rest_v[rest_f[:, 1]] - rest_v[rest_f[:, 0]],
                                    rest_v[rest_f[:, 2]] - rest_v[rest_f[:, 0]]), axis=1)
    assert areas.min() > 1e-6, "degenerate triangle in a sample rest mesh"
    for group, spec in constraints["handles"].items():
        if isinstance(spec, list):
            assert all(0 <= i < len(rest_v) for i in spec), group
        else:
            near = np.linalg.norm(rest_v - np.array(spec["near"]), axis=1) <= spec["radius"]
            assert near.any(), f"handle region {group} selects no vertex"


def test_wings_are_exactly_symmetric_about_x_zero(samples_dir):
    """The wings set (the Drag to Pose tool's Mirror check): vertices, triangles and every example
    mirror onto themselves across the plane x = 0."""
    folder = samples_dir / "wings"
    rest, faces = read_obj(folder / "rest.obj")
    image = rest * [-1, 1, 1]
    mate = np.array([np.argmin(np.linalg.norm(rest - p, axis=1)) for p in image])
    assert np.array_equal(rest[mate], image)
    triangles = {tuple(sorted(f)) for f in faces.tolist()}
    assert all(tuple(sorted(mate[f])) in triangles for f in faces)
    for example in sorted(folder.glob("example_*.obj")):
        pose = read_obj(example)[0]
        assert np.array_equal(pose[mate], pose * [-1, 1, 1]), example.name

