"""Every .glb variant (meshopt and quantized, each with a morph basis and with one target per frame;
draco) read back by clients the project did not write:
three.js GLTFLoader with the meshoptimizer package's MeshoptDecoder (playing the clip to each key)
and glTF-Transform, both in Node (tests/node/decode_glb.mjs); each frame matches the solver's
within the variant's grid; the Khronos validator reports nothing above info."""
import json
import subprocess

import numpy as np
import pytest

from meshik.export.glb_reader import read_animation_glb
from meshik.inputs.meshio import load_mesh
from meshik.pipeline import pose_job
from pipeline_clients import ROOT, validate_and_check_no_errors

DECODER = ROOT / "tests" / "node" / "decode_glb.mjs"
# three.js's GLTFLoader decodes Draco only through DRACOLoader's web worker and wasm, which Node lacks:
# the Draco variant is read by glTF-Transform here and by Google's draco_decoder in test_pipeline_pose.
CLIENTS = {"meshopt": ("three", "transform"), "meshopt per frame": ("three", "transform"),
           "quantized": ("three", "transform"), "quantized per frame": ("three", "transform"), "draco": ("transform",)}
# label: (--glb, --glb-targets)
JOBS = {"meshopt": ("meshopt", "basis"), "meshopt per frame": ("meshopt", "frames"), "quantized": ("quantized", "basis"),
        "quantized per frame": ("quantized", "frames"), "draco": ("draco", "basis")}


@pytest.fixture(scope="module", params=[None, 160], ids=["full", "simplified"])
def jobs(request, samples_dir, tmp_path_factory):
    """{label: (job folder, report, #frames by #V by 3 solver frames)} for the bar sample, full
    resolution and simplified (vertex ids that are not the rows)."""
    out = {}
    for label, (variant, targets) in JOBS.items():
        folder = tmp_path_factory.mktemp(variant)
        report = pose_job(samples_dir / "bar" / "animation.json", folder, formats=("drc", "glb", "ply"), glb=variant,
                          glb_targets=targets, simplify=request.param, quiet=True)
        frames = np.stack([load_mesh(folder / "frames" / f"{f['name']}.ply")[0] for f in report["frames"]])
        out[label] = (folder, report, frames)
    return out


def decode_with(client: str, glb, scratch):
    """(summary, #frames by #V by 3 positions, #V ids) as the Node client decodes the .glb."""
    raw = scratch / f"{glb.stem}.{client}.bin"
    done = subprocess.run(["node", str(DECODER), client, str(glb), str(raw)], capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    values = np.fromfile(raw, dtype="<f8")
    count = summary["frames"] * summary["vertices"] * 3
    return summary, values[:count].reshape(summary["frames"], summary["vertices"], 3), values[count:].astype(np.int64)


@pytest.mark.parametrize("variant", list(CLIENTS))
def test_every_client_decodes_every_frame_within_the_grid(jobs, variant, tmp_path):
    folder, report, solver = jobs[variant]
    glb = folder / "animation.glb"
    entry = report["compressed_outputs"]["animation.glb"]
    assert entry["variant"] == JOBS[variant][0] and entry["bytes"] == glb.stat().st_size == report["outputs"]["animation.glb"]
    ids = np.arange(len(solver[0])) if report["simplification"] is None \
        else np.loadtxt(folder / "vertex_ids.txt", dtype=np.int64).reshape(-1)
    row_of_id = {int(i): row for row, i in enumerate(ids)}
    # quantized variants: the grid point nearest each position; Draco: float32 deltas on the Draco base
    tolerance = entry["grid_step"] * np.sqrt(3) / 2 * 1.001 if variant != "draco" else 1e-5
    for client in CLIENTS[variant]:
        summary, frames, decoded_ids = decode_with(client, glb, tmp_path)
        assert summary["frames"] == len(solver) and summary["vertices"] == len(solver[0]), client
        assert sorted(decoded_ids) == sorted(ids), client
        expected = solver[:, [row_of_id[int(i)] for i in decoded_ids]]
        error = np.linalg.norm(frames - expected, axis=2)
        assert error.max() <= tolerance, (client, error.max(), tolerance)
        np.testing.assert_allclose(summary["times"], np.arange(len(solver)) / report["fps"], rtol=1e-6)
        if client == "three":  # the clip plays: at key k the mixer gives the targets the file's weights of key k
            weights = read_animation_glb(glb.read_bytes()).weights
            np.testing.assert_allclose(summary["weightsAtKeys"], weights, atol=1e-6)
    # the report's error is the same measure (over the animation's bounding-box diagonal)
    points = solver.reshape(-1, 3)
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    assert entry["max_position_error"] <= tolerance / diagonal
    assert 0 < report["compressed_outputs"]["frames/*.drc"]["max_position_error"] <= report["quantization"]["step"] / diagonal


@pytest.mark.parametrize("variant", list(CLIENTS))
def test_khronos_validator_reports_no_error_or_warning(jobs, variant):
    folder, _, _ = jobs[variant]
    issues = validate_and_check_no_errors(folder / "animation.glb")
    assert {m["code"] for m in issues["messages"]} <= {"UNSUPPORTED_EXTENSION", "UNUSED_OBJECT"}


def test_meshopt_is_the_smallest_and_quantized_needs_no_decoder(jobs):
    sizes = {label: report["compressed_outputs"]["animation.glb"]["bytes"] for label, (_, report, _) in jobs.items()}
    assert sizes["meshopt"] < sizes["meshopt per frame"] < sizes["draco"] and sizes["meshopt"] < sizes["quantized"]
    targets = {label: report["compressed_outputs"]["animation.glb"]["morph_targets"]
               for label, (_, report, _) in jobs.items()}
    frames = jobs["draco"][1]["frame_count"]
    # the bar bends smoothly: a few basis targets carry its frames
    assert targets["meshopt"] == targets["quantized"] < frames == targets["meshopt per frame"] == targets["draco"]
    document = {}
    for variant, (folder, _, _) in jobs.items():
        data = (folder / "animation.glb").read_bytes()
        length = int.from_bytes(data[12:16], "little")
        document[variant] = json.loads(data[20:20 + length])
    assert document["meshopt"]["extensionsRequired"] == ["KHR_mesh_quantization", "EXT_meshopt_compression"]
    assert document["quantized"]["extensionsRequired"] == ["KHR_mesh_quantization"]
    assert document["draco"]["extensionsRequired"] == ["KHR_draco_mesh_compression"]
