"""SIGKILL while a job moves its outputs into place never leaves a report that lies (issue 12, defect 5).

A re-run replaces a complete job folder (other options, so every frame changes). The test kills it
at random moments of the commit, found by watching the folder, and checks the invariant commit()
keeps: whenever report.json is present, every file it lists has exactly the listed bytes; when it
is absent the folder is marked incomplete and the next run completes it."""
import hashlib
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

from meshik.outputs.staging import REPORT_NAME

MESHIK = Path(sys.executable).parent / "meshik"


def report_is_truthful(folder: Path) -> bool:
    """True when report.json is absent, or lists only files whose bytes match its SHA-256s."""
    try:
        report = json.loads((folder / REPORT_NAME).read_text())
    except FileNotFoundError:
        return True
    for name, digest in report["output_sha256"].items():
        path = folder / name
        if not path.is_file() or hashlib.sha256(path.read_bytes()).hexdigest() != digest:
            return False
    return True


def test_a_run_killed_during_its_commit_leaves_a_truthful_folder(samples_dir, tmp_path):
    shutil.copytree(samples_dir / "bar", tmp_path / "in")
    document = json.loads((tmp_path / "in" / "animation.json").read_text())
    document["frames"] = [{"targets": {"tip": {"translate": [0, 0.002 * k, 0]}}} for k in range(600)]
    shot = tmp_path / "in" / "shot.json"
    shot.write_text(json.dumps(document))
    out = tmp_path / "out"
    pose = [str(MESHIK), "pose", str(shot), "--out", str(out), "--quiet", "--format", "drc,ply"]
    assert subprocess.run(pose + ["--quantization-bits", "12"]).returncode == 0
    rng = random.Random(12)
    killed_in_commit = 0
    for bits in (13, 14, 15, 16):
        run = subprocess.Popen(pose + ["--quantization-bits", str(bits)])
        marker = out / ".meshik-replaced-report.json"
        while run.poll() is None and not marker.exists():
            time.sleep(0.0005)
        if run.poll() is None:
            time.sleep(rng.uniform(0, 0.02))
            run.send_signal(signal.SIGKILL)
            killed_in_commit += 1
        run.wait()
        assert report_is_truthful(out), f"killed during the commit of the {bits}-bit run"
    assert killed_in_commit >= 2, "the commits were too quick to be interrupted"
    assert subprocess.run(pose + ["--quantization-bits", "16"]).returncode == 0
    assert (out / REPORT_NAME).exists() and report_is_truthful(out)
    assert json.loads((out / REPORT_NAME).read_text())["quantization"]["bits"] == 16
    assert not any(p.name.startswith(".meshik") for p in out.iterdir())
