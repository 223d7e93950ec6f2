"""A whole animation: the 48-frame horse gallop reconstructed from a dozen handle vertices, posed
with the horse-poses examples, through load, pose and export (real data, skipped when absent)."""
import json

import numpy as np
import pytest

from meshik.export import draco as export_draco
from meshik.inputs.meshio import load_mesh
from meshik.pipeline import pose_job
from meshik.inputs.tracking import farthest_point_handles, tracking_document
from conftest import example_set_files
from pipeline_clients import validate_and_check_no_errors


@pytest.fixture(scope="module")
def gallop(shared_data, tmp_path_factory):
    """The gallop frames and a constraint file tracking 12 spread-out vertices of them."""
    folder = shared_data / "horse-gallop"
    if not folder.is_dir():
        pytest.skip(f"{folder} not found")
    rest_path, example_paths = example_set_files(shared_data / "horse-poses")
    rest, _ = load_mesh(rest_path)
    frames = {p.stem: load_mesh(p)[0] for p in sorted(folder.glob("*.obj")) if p.stem.isdigit()}
    handles = farthest_point_handles(rest, 12)
    path = tmp_path_factory.mktemp("gallop") / "gallop.json"
    path.write_text(json.dumps(tracking_document(path, rest_path, example_paths, frames, handles)))
    return {"path": path, "frames": frames, "handles": handles, "rest": rest}


def test_gallop_end_to_end(gallop, tmp_path):
    report = pose_job(gallop["path"], tmp_path, formats=("drc", "glb"), quiet=True)
    assert report["frame_count"] == 48 and report["solver"]["handle_vertices"] == 12
    assert report["handle_fit_error"]["max"] < 1e-8
    validate_and_check_no_errors(tmp_path / "gallop.glb")
    diagonal = np.linalg.norm(np.ptp(gallop["rest"], axis=0))
    errors, unposed = [], []
    for name, truth in gallop["frames"].items():
        decoded = export_draco.decode((tmp_path / "frames" / f"{name}.drc").read_bytes())
        errors.append(rms_distance(decoded.vertices, truth[decoded.vertex_ids]))
        unposed.append(rms_distance(gallop["rest"], truth))
    errors, unposed = np.array(errors) / diagonal, np.array(unposed) / diagonal
    print(f"\ngallop: 48 frames, handle fit error {report['handle_fit_error']['max']:.2e}, "
          f"RMS distance to the true frames / bbox diagonal: mean {errors.mean():.4f}, worst {errors.max():.4f} "
          f"(rest pose: mean {unposed.mean():.4f}); pipeline {report['timings']['total']:.2f} s")
    # 12 tracked vertices and 10 examples of other motions: well below the rest pose's distance, every frame
    assert errors.mean() < 0.5 * unposed.mean() and np.all(errors < unposed)


def rms_distance(a, b):
    """Root mean square of the distances between corresponding rows of two #V by 3 arrays."""
    return float(np.sqrt(np.mean(np.sum((a - b) ** 2, axis=1))))
