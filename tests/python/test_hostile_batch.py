"""A batch whose first job's example set is large next to the worker's memory limit (issue 23).

Before: `meshik batch big.json t1.json t2.json --jobs 1 --memory-limit 300MB` (big: a 90,000-vertex
grid) kept the big example set in the worker's cache after the first job, above Dask's pause
threshold (80% of the limit): the worker paused for ever and the batch never ended, silently. Now a
worker trims its cache after each job while above 85% of the pause threshold, and the batch ends.
"""
import json
import shutil

import numpy as np

from hostile_checks import run_meshik
from pipeline_meshes import bump, grid, write_obj


def test_a_large_cached_example_set_does_not_pause_the_worker(tmp_path, samples_dir):
    vertices, faces = grid(300, 1.0)  # 90,000 vertices
    folder = tmp_path / "in"
    folder.mkdir()
    write_obj(folder / "rest.obj", vertices, faces)
    write_obj(folder / "up.obj", bump(vertices, (0.5, 0.5), 0.2, 0.2), faces)
    write_obj(folder / "down.obj", bump(vertices, (0.5, 0.5), -0.2, 0.2), faces)
    corner = [0, 1, 300, 301]
    centre = [int(np.argmin(np.linalg.norm(vertices[:, :2] - 0.5, axis=1)))]
    document = {"format": "meshik-constraints", "version": 1, "rest": "rest.obj", "examples": ["up.obj", "down.obj"],
                "handles": {"corner": corner, "centre": centre},
                "frames": [{"targets": {"centre": {"translate": [0, 0, 0.05 * k]}}} for k in range(3)]}
    (folder / "big.json").write_text(json.dumps(document))
    for name in ("t1", "t2"):
        shutil.copytree(samples_dir / "bar", folder / name)
        (folder / name / "animation.json").rename(folder / f"{name}.json.tmp")
        text = (folder / f"{name}.json.tmp").read_text().replace('"rest.obj"', f'"{name}/rest.obj"') \
            .replace('"example_1.obj"', f'"{name}/example_1.obj"').replace('"example_2.obj"', f'"{name}/example_2.obj"')
        (folder / f"{name}.json").write_text(text)
        (folder / f"{name}.json.tmp").unlink()
    outcome = run_meshik(["batch", folder / "big.json", folder / "t1.json", folder / "t2.json", "--jobs", "1",
                          "--memory-limit", "300MB", "--out", tmp_path / "out", "--quiet", "--format", "drc"], timeout=400)
    assert not outcome.timed_out, "the batch did not end (a paused worker?)"
    assert not outcome.left_behind
    report = json.loads((tmp_path / "out" / "batch-report.json").read_text())
    assert {job["name"]: job["status"] for job in report["jobs"]}.keys() == {"big", "t1", "t2"}
    assert report["done"] + report["skipped"] >= 2, report  # the small jobs at least ran after the big one
