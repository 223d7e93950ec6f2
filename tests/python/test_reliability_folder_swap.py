"""A batch's job folder is replaced in one swap: all old or all new at every instant (issue 12, defect 5).

A child process commits generation after generation of a job folder inside an owned output folder
and is SIGKILLed at random moments, many of them inside commit(); after each kill the folder must be
exactly one complete generation (its report lists exactly the files present, with their bytes), and
a user's own files in it survive every swap.
"""
import hashlib
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from meshik.outputs import folder_swap
from meshik.outputs.staging import REPORT_NAME, StagedOutput

FRAMES = 200
_WRITER = r"""
import sys
from pathlib import Path
from meshik.outputs.staging import StagedOutput
out, generation, marker = Path(sys.argv[1]), int(sys.argv[2]), Path(sys.argv[3])
with StagedOutput(out / "job", within=out) as staged:
    for i in range({frames}):
        staged.write(f"frames/{{i:04d}}.bin", f"generation {{generation}} frame {{i}}".encode() * 50)
    marker.write_text("committing")
    staged.commit({{"generation": generation}})
"""


def write_generation(out: Path, generation: int, marker: Path) -> subprocess.Popen:
    """A child process that writes and commits one generation of out/job."""
    return subprocess.Popen([sys.executable, "-c", _WRITER.format(frames=FRAMES), str(out), str(generation), str(marker)])


def whole_generation(job: Path) -> int:
    """The generation the job folder holds, asserting that it holds exactly one, completely."""
    report = json.loads((job / REPORT_NAME).read_text())
    listed = set(report["output_sha256"])
    present = {p.relative_to(job).as_posix() for p in (job / "frames").iterdir()}
    assert present == {name for name in listed if name.startswith("frames/")}, "files of two generations"
    for name, digest in report["output_sha256"].items():
        data = (job / name).read_bytes()
        assert hashlib.sha256(data).hexdigest() == digest, f"{name} does not have the listed bytes"
        assert data.startswith(f"generation {report['generation']} ".encode()), f"{name} is of another generation"
    return report["generation"]


def test_a_job_folder_killed_at_random_moments_is_always_one_whole_generation(tmp_path):
    out, marker = tmp_path / "out", tmp_path / "marker"
    assert write_generation(out, 0, marker).wait() == 0
    notes = out / "job" / "notes" / "shot.txt"
    notes.parent.mkdir()
    notes.write_text("the artist's own notes")
    rng = random.Random(5)
    seen, killed_while_committing = {0}, 0
    for generation in range(1, 13):
        marker.unlink(missing_ok=True)
        child = write_generation(out, generation, marker)
        while child.poll() is None and not marker.exists():
            time.sleep(0.0002)
        if child.poll() is None:
            time.sleep(rng.uniform(0, 0.003))
            child.send_signal(signal.SIGKILL)
            killed_while_committing += child.wait() == -signal.SIGKILL
        held = whole_generation(out / "job")
        assert held in (max(seen), generation), f"generation {held} after committing {generation}"
        seen.add(held)
        assert notes.read_text() == "the artist's own notes"
    assert killed_while_committing >= 3
    assert write_generation(out, 99, marker).wait() == 0
    assert whole_generation(out / "job") == 99 and notes.read_text() == "the artist's own notes"
    assert sorted(p.name for p in out.iterdir()) == ["job"], "a staging folder or the old folder was left"


def test_the_swap_keeps_what_no_run_provably_wrote(tmp_path):
    out = tmp_path / "out"
    with StagedOutput(out / "job", within=out) as staged:
        staged.write("a.bin", b"first a")
        staged.write("b.bin", b"first b")
        staged.commit({})
    (out / "job" / "b.bin").write_bytes(b"edited by hand")
    os.symlink("a.bin", out / "job" / "link")
    inode = (out / "job" / "b.bin").stat().st_ino
    with StagedOutput(out / "job", within=out) as staged:
        staged.write("c.bin", b"second c")
        staged.commit({})
    job = out / "job"
    assert sorted(p.name for p in job.iterdir()) == ["b.bin", "c.bin", "link", REPORT_NAME]
    assert (job / "b.bin").read_bytes() == b"edited by hand" and (job / "b.bin").stat().st_ino == inode
    assert os.readlink(job / "link") == "a.bin"
    assert json.loads((job / REPORT_NAME).read_text())["outputs"] == {"c.bin": 8}


def test_without_an_atomic_swap_the_commit_moves_file_by_file(tmp_path, monkeypatch):
    monkeypatch.setattr(folder_swap, "_RENAMEAT2", None)
    out = tmp_path / "out"
    for generation in (1, 2):
        with StagedOutput(out / "job", within=out) as staged:
            staged.write(f"g{generation}.bin", b"x" * generation)
            staged.commit({"generation": generation})
    assert sorted(p.name for p in (out / "job").iterdir()) == ["g2.bin", REPORT_NAME]
    assert sorted(p.name for p in out.iterdir()) == ["job"]


def test_a_fifo_in_the_old_folder_is_kept_by_the_file_by_file_commit(tmp_path):
    out = tmp_path / "out"
    for generation in (1, 2):
        with StagedOutput(out / "job", within=out) as staged:
            staged.write(f"g{generation}.bin", b"x")
            staged.commit({})
        if generation == 1:
            os.mkfifo(out / "job" / "pipe")
    assert sorted(p.name for p in (out / "job").iterdir()) == ["g2.bin", "pipe", REPORT_NAME]


@pytest.mark.parametrize("name", [REPORT_NAME, ".meshik-replaced-report.json"])
def test_an_output_may_not_take_a_name_the_run_keeps(tmp_path, name):
    with StagedOutput(tmp_path / "out") as staged:
        with pytest.raises(ValueError, match="keeps for itself"):
            staged.write(name, b"{}")
