"""Batch runs on Dask: a failing job does not stop the others, complete jobs are skipped, job names
stay inside --out, and a run killed at any moment leaves no file under its final name that is not
complete. The cluster tests (test_batch_cluster.py) cover worker deaths and interrupts."""
import json
import socket
import subprocess
import sys
import time

import pytest

from meshik import batch
from meshik.export import draco as export_draco
from meshik.export.glb_reader import read_animation_glb
from meshik.batch import SUMMARY_NAME, job_names
from meshik.cli import main
from meshik.errors import PipelineError
from meshik.inputs.meshio import load_mesh
from meshik.outputs.staging import REPORT_NAME
from pipeline_meshes import tube_constraints, write_constraints, write_tube_set


@pytest.fixture()
def shots(tmp_path):
    """Two valid constraint files and one naming a missing example, over one tube set."""
    tube_set = write_tube_set(tmp_path / "in", rings=8, segments=6)
    walk = write_constraints(tmp_path / "in" / "walk.json", tube_constraints(tube_set, frames=3))
    run = write_constraints(tmp_path / "in" / "run.json", tube_constraints(tube_set, frames=4, top_degrees=[10, 20, 30, 40]))
    broken_doc = tube_constraints(tube_set, frames=2)
    broken_doc["examples"] = ["example_1.obj", "example_9.obj"]
    broken = write_constraints(tmp_path / "in" / "broken.json", broken_doc)
    return [walk, broken, run]


def test_failing_job_does_not_stop_the_others(shots, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["batch", *map(str, shots), "--out", str(out), "--jobs", "2", "--format", "drc,ply"]) == 1
    error = capsys.readouterr().err
    assert "broken: FAILED: " in error and "examples[1]: mesh file not found" in error
    assert "1 of 3 jobs failed: broken" in error
    summary = json.loads((out / SUMMARY_NAME).read_text())
    assert [job["status"] for job in summary["jobs"]] == ["done", "failed", "done"] and summary["failed"] == 1
    assert not (out / "broken").exists()
    for name, frames in (("walk", 3), ("run", 4)):
        report = json.loads((out / name / REPORT_NAME).read_text())
        assert report["frame_count"] == frames
        assert sorted(report["outputs"]) == sorted([f"frames/{k:04d}.{ext}" for k in range(1, frames + 1) for ext in ("drc", "ply")])

    # a re-run skips the complete jobs and still reports the failing one
    assert main(["batch", *map(str, shots), "--out", str(out), "--jobs", "2", "--format", "drc,ply"]) == 1
    summary = json.loads((out / SUMMARY_NAME).read_text())
    assert [job["status"] for job in summary["jobs"]] == ["skipped", "failed", "skipped"]
    # other options make other outputs: the job runs again
    assert main(["batch", str(shots[0]), "--out", str(out), "--jobs", "1", "--format", "glb", "--quiet"]) == 0
    assert json.loads((out / SUMMARY_NAME).read_text())["jobs"][0]["status"] == "done"
    assert sorted(json.loads((out / "walk" / REPORT_NAME).read_text())["outputs"]) == ["walk.glb"]
    assert not (out / "walk" / "frames" / "0001.drc").exists()  # outputs of the earlier options removed


def test_job_names_disambiguate_by_folder(tmp_path):
    assert job_names([tmp_path / "a" / "shot.json", tmp_path / "b" / "shot.json", tmp_path / "walk.json"]) == \
        ["a-shot", "b-shot", "walk"]
    with pytest.raises(PipelineError, match="would both write to the job folder"):
        job_names([tmp_path / "shot.json", tmp_path / "shot.json"])


def test_local_cluster_options_conflict_with_a_scheduler(shots, tmp_path, capsys):
    assert main(["batch", str(shots[0]), "--out", str(tmp_path / "out"), "--scheduler", "tcp://127.0.0.1:1",
                 "--jobs", "2", "--retries", "1"]) == 2
    assert "--jobs, --retries set up the local cluster" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def no_partial_file(folder):
    """Every visible file in a job folder is whole: it decodes / parses; with a report.json, every
    file the report lists is there at its size. (A kill between two renames of the commit may leave
    some whole files without a report: the job then simply runs again.)"""
    visible = [p for p in folder.rglob("*") if p.is_file() and not any(part.startswith(".") for part in p.relative_to(folder).parts)]
    for path in visible:
        if path.suffix == ".drc":
            assert len(export_draco.decode(path.read_bytes()).faces) > 0, path
        elif path.suffix == ".glb":
            assert len(read_animation_glb(path.read_bytes()).frames) > 0, path
        elif path.suffix == ".json":
            report = json.loads(path.read_text())
            for name, size in report.get("outputs", {}).items():
                assert (folder / name).stat().st_size == size, name
        else:
            assert len(load_mesh(path)[1]) > 0, path
    return True


@pytest.mark.parametrize("delay", [0.0, 0.02, 0.05, 0.1, 0.2])
def test_killed_job_leaves_no_partial_file(tmp_path, delay):
    """Kill a job (SIGKILL: no clean-up at all) `delay` seconds after it starts writing its outputs."""
    tube_set = write_tube_set(tmp_path / "in", rings=20, segments=16)
    shot = write_constraints(tmp_path / "in" / "long.json", tube_constraints(tube_set, frames=40))
    out = tmp_path / "out"
    process = subprocess.Popen([sys.executable, "-c", "import sys; from meshik.cli import main; sys.exit(main())",
                                "pose", str(shot), "--out", str(out), "--format", "drc,ply,obj,glb", "--quiet"])
    while process.poll() is None and not (out.exists() and any(out.glob(".meshik-partial-*"))):
        time.sleep(0.002)
    time.sleep(delay)
    process.kill()
    process.wait()
    assert out.exists() and no_partial_file(out)


def test_an_unreachable_scheduler_is_one_line(shots, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(batch, "SCHEDULER_TIMEOUT", "1s")
    with socket.socket() as probe:  # a port nothing listens on
        probe.bind(("127.0.0.1", 0))
        address = f"tcp://127.0.0.1:{probe.getsockname()[1]}"
    assert main(["batch", str(shots[0]), "--out", str(tmp_path / "out"), "--scheduler", address]) == 1
    assert capsys.readouterr().err.startswith(f"meshik: error: cannot reach the Dask scheduler at {address}: ")
    assert not (tmp_path / "out").exists()
