"""A disk that fills while a run writes: one line naming the folder and file, nothing lost (issue 12).

The output folder is a small tmpfs mounted for the test (root only; skipped with the reason where
mounting is not allowed). The run must exit 1 with one line, leave no staging folder, keep every
file that was there before, and leave an earlier complete result exactly as it was.
"""
import hashlib
import subprocess
import sys
from pathlib import Path

import pytest

MESHIK = Path(sys.executable).parent / "meshik"


@pytest.fixture
def small_disk(tmp_path):
    """A function mounting a tmpfs of `kib` KiB at a fresh folder and returning it; unmounted after."""
    mounted = []

    def mount(kib: int) -> Path:
        folder = tmp_path / f"disk{len(mounted)}"
        folder.mkdir()
        done = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kib}k", "tmpfs", str(folder)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            pytest.skip(f"cannot mount a small tmpfs here ({done.stderr.strip() or 'mount failed'}): small-disk test skipped")
        mounted.append(folder)
        return folder

    yield mount
    for folder in mounted:
        subprocess.run(["umount", "-l", str(folder)], check=False)


def snapshot(folder: Path) -> dict:
    """{relative path: SHA-256} of every file below `folder`."""
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def pose(constraints: Path, out: Path, *options: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(MESHIK), "pose", str(constraints), "--out", str(out), "--quiet", *options],
                          capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("formats", ["drc", "ply", "drc,glb,obj"])
def test_a_full_disk_is_one_line_naming_the_file_and_loses_nothing(samples_dir, small_disk, formats):
    disk = small_disk(64)
    (disk / "keep.txt").write_text("the user's file")
    done = pose(samples_dir / "bar" / "animation.json", disk / "out", "--format", formats)
    assert done.returncode == 1, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in done.stderr, done.stderr
    assert lines[0].startswith(f"meshik: error: {disk / 'out'}: ") and "frames/" in lines[0], lines[0]
    assert "bytes free on that disk" in lines[0]
    assert snapshot(disk) == {"keep.txt": hashlib.sha256(b"the user's file").hexdigest()}
    assert sorted(p.name for p in disk.iterdir()) == ["keep.txt"], "a staging folder or an empty --out was left"


def test_an_earlier_result_survives_a_rerun_that_fills_the_disk(samples_dir, small_disk, tmp_path):
    constraints = samples_dir / "bar" / "animation.json"
    assert pose(constraints, tmp_path / "sized", "--format", "drc").returncode == 0
    pages = sum(-(-p.stat().st_size // 4096) for p in (tmp_path / "sized").rglob("*") if p.is_file())
    disk = small_disk(pages * 4 * 3 // 2 + 16)     # room for one result (in 4 KiB pages), not for a second beside it
    out = disk / "out"
    assert pose(constraints, out, "--format", "drc").returncode == 0
    before = snapshot(out)
    done = pose(constraints, out, "--format", "drc", "--quantization-bits", "16")
    assert done.returncode == 1 and len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert snapshot(out) == before
    assert not [p.name for p in out.iterdir() if p.name.startswith(".meshik")]
