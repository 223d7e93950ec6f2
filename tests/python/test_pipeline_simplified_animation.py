"""A simplified job's frames are the simplification of the full-resolution job's frames (issue 29):
pose_job run at full resolution and with --simplify, its .ply frames compared with the full frames
restricted to the kept vertices (both decimators keep a subset of the original vertices), the
handles on their targets. Also on the horse gallop when ../shared/data is there."""
import json

import numpy as np
import pytest

from meshik.cli import main
from meshik.inputs.meshio import load_mesh
from meshik.pipeline import pose_job
from meshik.inputs.tracking import farthest_point_handles, tracking_document
from conftest import example_set_files

# the .ply frames carry the solver's doubles to within this fraction of the diagonal
TOLERANCE = 1e-9


def posed_frames(out, report):
    """(#frames by #V by 3 positions, #F by 3 triangles) of a job's .ply frames, in report order."""
    meshes = [load_mesh(out / "frames" / f"{frame['name']}.ply") for frame in report["frames"]]
    return np.stack([vertices for vertices, _ in meshes]), meshes[0][1]


def assert_simplified_full_frames(full_out, full_report, out, report, rest, rest_faces):
    """Every frame of the simplified job `out` is its full frame (of the job `full_out`) restricted to the
    kept vertices (vertex_ids.txt), to TOLERANCE of the diagonal; rest, rest_faces: the full rest mesh."""
    full, full_faces = posed_frames(full_out, full_report)
    frames, faces = posed_frames(out, report)
    ids = np.loadtxt(out / "vertex_ids.txt", dtype=np.int64)
    tolerance = TOLERANCE * np.linalg.norm(np.ptp(rest, axis=0))
    np.testing.assert_array_equal(full_faces, rest_faces)
    assert len(faces) <= report["simplification"]["triangles"] and frames.shape == (len(full), len(ids), 3)
    assert np.abs(frames - full[:, ids]).max() <= tolerance


@pytest.mark.parametrize("method", ["fast", "openmesh"])
def test_default_frames_are_the_simplified_full_frames(samples_dir, tmp_path, method):
    path = samples_dir / "limb" / "animation.json"
    full_report = pose_job(path, tmp_path / "full", formats=("ply",), quiet=True)
    report = pose_job(path, tmp_path / "simple", simplify=0.25, simplifier=method, formats=("ply",), quiet=True)
    rest, faces = load_mesh(samples_dir / "limb" / "rest.obj")
    assert report["simplification"]["posed"] == "full resolution"
    assert report["solver"]["posed_vertices"] == len(rest)
    bound = report["simplification"]["distance_bound"]  # openmesh's; None when lifted or for fast
    assert bound is None or bound > 0  # None when lifted
    assert report["simplification"]["merged_handle_vertices"] == 0  # locked
    assert report["handle_fit_error"]["max"] <= TOLERANCE * np.linalg.norm(np.ptp(rest, axis=0))
    assert_simplified_full_frames(tmp_path / "full", full_report, tmp_path / "simple", report, rest, faces)


def test_simplify_first_poses_the_simplified_examples(samples_dir, tmp_path):
    path = samples_dir / "limb" / "animation.json"
    default = pose_job(path, tmp_path / "out", simplify=0.25, formats=("ply",), quiet=True)
    assert main(["pose", str(path), "--out", str(tmp_path / "out"), "--simplify", "0.25", "--simplify-first",
                 "--format", "ply", "--quiet"]) == 0
    first = json.loads((tmp_path / "out" / "report.json").read_text())  # another job: its key differs
    assert first["simplification"]["posed"] == "simplified example set"
    assert first["solver"]["posed_vertices"] == default["simplification"]["vertices"]
    assert pose_job(path, tmp_path / "out", simplify=0.25, formats=("ply",), quiet=True, simplify_first=True)["skipped"]


def test_gallop_default_frames_are_the_simplified_full_frames(shared_data, tmp_path):
    """8 frames of the horse gallop (12 tracked handles, horse-poses as examples), both simplifiers at 4,000 triangles."""
    rest_path, example_paths = example_set_files(shared_data / "horse-poses")
    gallop = shared_data / "horse-gallop"
    if not gallop.is_dir():
        pytest.skip(f"{gallop} not found")
    rest, faces = load_mesh(rest_path)
    frames = {p.stem: load_mesh(p)[0] for p in sorted(gallop.glob("*.obj"))[:48:6] if p.stem.isdigit()}
    path = tmp_path / "gallop.json"
    path.write_text(json.dumps(tracking_document(path, rest_path, example_paths, frames, farthest_point_handles(rest, 12))))
    full_report = pose_job(path, tmp_path / "full", formats=("ply",), quiet=True)
    for method in ("fast", "openmesh"):
        report = pose_job(path, tmp_path / method, simplify=4000, simplifier=method, formats=("ply",), quiet=True)
        assert report["handle_fit_error"]["max"] < 1e-8 and report["simplification"]["triangles"] <= 4000
        assert_simplified_full_frames(tmp_path / "full", full_report, tmp_path / method, report, rest, faces)
