"""`meshik batch` on a real Dask cluster: a scheduler and two workers as separate processes on
127.0.0.1, a job whose worker is killed while it runs, one whose worker dies every time, bad
input, a job name that would leave --out; and the batch stopped by SIGTERM or Ctrl+C."""
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest
from distributed import Client

from dask_processes import LoopbackCluster, assert_all_gone
from meshik.batch import SUMMARY_NAME
from meshik.batch.job import KILL_WORKER_VARIABLE
from meshik.cli import main
from meshik.pipeline import pose_job
from meshik.outputs.staging import REPORT_NAME
from pipeline_meshes import tube_constraints, write_constraints, write_tube_set
from test_pipeline_batch import no_partial_file


def sample_shot(samples_dir: Path, sample: str, frames: slice, path: Path) -> Path:
    """A constraint file at `path` posing sample_meshes/<sample> through some of its frames (the
    meshes are referred to by absolute path, not copied)."""
    document = json.loads((samples_dir / sample / "animation.json").read_text())
    document["rest"] = str(samples_dir / sample / document["rest"])
    document["examples"] = [str(samples_dir / sample / e) for e in document["examples"]]
    document["frames"] = document["frames"][frames]
    path.write_text(json.dumps(document))
    return path


def files_under(root: Path, *skip: Path):
    """{relative path: (size, modification time)} of every file under root, outside the `skip` folders."""
    found = {}
    for path in root.rglob("*"):
        if path.is_file() and not any(path == s or s in path.parents for s in skip):
            stat = path.stat()
            found[str(path.relative_to(root))] = (stat.st_size, stat.st_mtime_ns)
    return found


def test_batch_on_a_loopback_cluster(tmp_path, samples_dir, capsys):
    inputs = tmp_path / "in"
    inputs.mkdir()
    good = [sample_shot(samples_dir, sample, frames, inputs / f"{sample}-{part}.json")
            for sample in ("bar", "flag", "limb") for part, frames in (("all", slice(None)), ("even", slice(0, None, 2)))]
    good.append(sample_shot(samples_dir, "limb", slice(1, None, 2), inputs / "limb-odd.json"))
    doomed = good.pop(good.index(inputs / "limb-even.json"))  # its worker dies every time it runs it
    broken = inputs / "broken.json"
    broken.write_text(json.dumps(dict(json.loads((inputs / "bar-all.json").read_text()), examples=[str(inputs / "missing.obj")])))
    escaping = inputs / "...json"  # its stem, "..", would be the folder above --out
    escaping.write_bytes((inputs / "bar-all.json").read_bytes())
    itself = inputs / "..json"  # its stem, ".", would be --out itself
    itself.write_bytes((inputs / "bar-all.json").read_bytes())
    shots = good + [doomed, broken, escaping, itself]
    assert len(shots) >= 8

    local = tmp_path / "local"
    for shot in good:
        pose_job(shot, local / shot.stem, quiet=True)
    out, cluster_folder = tmp_path / "out", tmp_path / "cluster"
    killed_once, killed_always = tmp_path / "killed-once.txt", tmp_path / "killed-always.txt"
    kill = f"flag-even,1,{killed_once};limb-even,99,{killed_always}"
    before = files_under(tmp_path, out, cluster_folder), files_under(samples_dir)

    with LoopbackCluster(cluster_folder, workers=2, worker_env={KILL_WORKER_VARIABLE: kill},
                         scheduler_env={"DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "1",
                                        "DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION": "1.0"}) as cluster:
        assert main(["batch", *map(str, shots), "--out", str(out), "--scheduler", cluster.address]) == 1
        error = capsys.readouterr().err
        report = {job["name"]: job for job in json.loads((out / SUMMARY_NAME).read_text())["jobs"]}

        # a second run skips every complete job
        assert main(["batch", *map(str, good), "--out", str(out), "--scheduler", cluster.address, "--quiet"]) == 0
        again = json.loads((out / SUMMARY_NAME).read_text())
        assert [job["status"] for job in again["jobs"]] == ["skipped"] * len(good), (report, again)

    assert {name: job["status"] for name, job in report.items()} == dict(
        {shot.stem: "done" for shot in good}, **{"limb-even": "crashed", "broken": "failed", "..": "failed", ".": "failed"}), "\n".join(f"{n}: {j['reason']}" for n, j in report.items())
    assert f"broken: FAILED: {broken}: examples[0]: mesh file not found" in error
    assert f"..: FAILED: {escaping}: job name '..' cannot be used as a file name inside {out}" in error
    assert f".: FAILED: {itself}: job name '.' cannot be used as a file name inside {out}" in error
    assert f"limb-even: CRASHED: {doomed}: the worker process died each time it ran this job (2 runs" in error
    assert f"4 of {len(shots)} jobs failed: limb-even, broken, .., ." in error

    # the job whose worker was killed once ran again in another process and completed
    assert len(killed_once.read_text().split()) == 1 and len(killed_always.read_text().split()) == 2
    assert report["flag-even"]["worker"].split(":")[-1] not in killed_once.read_text().split()

    # every good job's outputs are those of a plain local run, byte for byte
    for shot in good:
        batch_report = json.loads((out / shot.stem / REPORT_NAME).read_text())
        local_report = json.loads((local / shot.stem / REPORT_NAME).read_text())
        assert batch_report["outputs"] == local_report["outputs"] and batch_report["outputs"]
        for name in batch_report["outputs"]:
            assert (out / shot.stem / name).read_bytes() == (local / shot.stem / name).read_bytes(), name
        assert [f["weights"] for f in batch_report["frames"]] == [f["weights"] for f in local_report["frames"]]

    # nothing written outside --out: the inputs and the samples are untouched, no job folder for the failures
    assert files_under(tmp_path, out, cluster_folder, killed_once, killed_always) == before[0]
    assert files_under(samples_dir) == before[1]
    assert sorted(p.name for p in out.iterdir()) == sorted([SUMMARY_NAME] + [shot.stem for shot in good])


def test_local_cluster_retries_are_configurable(tmp_path, samples_dir, capsys, monkeypatch):
    """--retries sets how often the local cluster re-runs a job whose worker died."""
    shots = [sample_shot(samples_dir, "bar", slice(0, 4), tmp_path / f"{name}.json") for name in ("calm", "doomed")]
    killed = tmp_path / "killed.txt"
    monkeypatch.setenv(KILL_WORKER_VARIABLE, f"doomed,1,{killed}")  # dies once only
    assert main(["batch", *map(str, shots), "--out", str(tmp_path / "out"), "--jobs", "1", "--retries", "0"]) == 1
    assert f"doomed: CRASHED: {shots[1]}: the worker process died each time it ran this job (1 run:" in capsys.readouterr().err
    killed.unlink()
    assert main(["batch", *map(str, shots), "--out", str(tmp_path / "out"), "--jobs", "1", "--retries", "1"]) == 0
    report = json.loads((tmp_path / "out" / SUMMARY_NAME).read_text())["jobs"]
    assert [job["status"] for job in report] == ["skipped", "done"] and len(killed.read_text().split()) == 1


def slow_shots(folder: Path, count: int):
    """`count` constraint files over one tube set, each some seconds of work (many frames, PLY and OBJ too)."""
    tube_set = write_tube_set(folder, rings=24, segments=20)
    return [write_constraints(folder / f"shot{k}.json", tube_constraints(tube_set, frames=80 + k)) for k in range(count)]


FORMATS = ["--format", "drc,glb,ply,obj"]


def interrupt_after_first_job(shots, out: Path, options, stop: str):
    """Run `meshik batch` on the shots in a process of its own; once a job is complete, stop it
    (SIGTERM, or Ctrl+C: SIGINT to its whole process group) and wait. Returns the processes it
    had started (itself included) and its output."""
    command = [sys.executable, "-c", "import sys; from meshik.cli import main; sys.exit(main())", "batch",
               *map(str, shots), "--out", str(out), *FORMATS, *options]
    batch = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             start_new_session=True)
    deadline = time.monotonic() + 120
    while not any(out.glob(f"*/{REPORT_NAME}")):  # at least one job complete, others running
        assert batch.poll() is None and time.monotonic() < deadline, batch.stdout.read().decode()
        time.sleep(0.02)
    processes = [psutil.Process(batch.pid)] + psutil.Process(batch.pid).children(recursive=True)
    if stop == "SIGTERM":
        batch.send_signal(signal.SIGTERM)
    else:  # a terminal's Ctrl+C reaches every process of the foreground group
        os.killpg(batch.pid, signal.SIGINT)
    output = batch.communicate(timeout=60)[0].decode()
    assert batch.returncode == 130, output
    return processes, output


def check_stopped_cleanly(shots, out: Path):
    """Nothing is written any more, nothing visible is partial, the report lists every job;
    returns the names of the jobs complete on disk (some, not all)."""
    settled = sorted(p for p in out.rglob("*"))
    time.sleep(1.5)
    assert sorted(p for p in out.rglob("*")) == settled
    for folder in out.iterdir():
        if folder.is_dir():
            assert no_partial_file(folder)
    first = json.loads((out / SUMMARY_NAME).read_text())["jobs"]
    assert len(first) == len(shots) and {job["status"] for job in first} <= {"done", "interrupted"}
    finished = {folder.name for folder in out.iterdir() if (folder / REPORT_NAME).exists()}
    assert {job["name"] for job in first if job["status"] == "done"} <= finished
    assert finished and len(finished) < len(shots)
    return finished


def check_rerun_finishes_the_rest(shots, out: Path, finished, options):
    """A second run skips the complete jobs and does the others."""
    assert main(["batch", *map(str, shots), "--out", str(out), *FORMATS, "--quiet", *options]) == 0
    second = {job["name"]: job["status"] for job in json.loads((out / SUMMARY_NAME).read_text())["jobs"]}
    assert second == {shot.stem: "skipped" if shot.stem in finished else "done" for shot in shots}


@pytest.mark.parametrize("stop", ["SIGTERM", "Ctrl+C"])
def test_interrupted_batch_stops_cleanly_and_resumes(tmp_path, stop):
    shots, out = slow_shots(tmp_path / "in", 8), tmp_path / "out"
    processes, _ = interrupt_after_first_job(shots, out, ["--jobs", "2"], stop)
    assert len(processes) >= 3  # the batch and its two workers at least
    assert_all_gone(processes)
    finished = check_stopped_cleanly(shots, out)
    check_rerun_finishes_the_rest(shots, out, finished, ["--jobs", "2"])


def test_interrupted_batch_on_a_cluster_stops_its_jobs(tmp_path):
    """On a cluster that outlives the batch, the workers running its jobs are restarted."""
    shots, out = slow_shots(tmp_path / "in", 8), tmp_path / "out"
    with LoopbackCluster(tmp_path / "cluster", workers=2,
                         scheduler_env={"DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION": "1.0"}) as cluster:
        with Client(cluster.address) as client:
            client.wait_for_workers(2)
            before = set(client.scheduler_info()["workers"])
            interrupt_after_first_job(shots, out, ["--scheduler", cluster.address], "SIGTERM")
            finished = check_stopped_cleanly(shots, out)
            assert not any(client.processing().values())  # nothing of the batch is left on the cluster
            client.wait_for_workers(2, timeout=60)
            assert set(client.scheduler_info()["workers"]) != before  # (at least one) restarted
        check_rerun_finishes_the_rest(shots, out, finished, ["--scheduler", cluster.address])
