"""Outputs appear complete or not at all; completed jobs are recognised; nothing is created for an
unusable destination."""
import os

import pytest

from meshik.errors import OutputError
from meshik.outputs.staging import REPORT_NAME, StagedOutput, check_writable, is_complete, read_report


def test_commit_moves_files_and_writes_report_last(tmp_path):
    destination = tmp_path / "job"
    with StagedOutput(destination) as staged:
        staged.write("frames/0001.drc", b"abc")
        staged.write("job.glb", b"12345")
        assert not (destination / "job.glb").exists()  # nothing under its final name before commit
        report = staged.commit({"job_key": "k1"})
    assert (destination / "frames/0001.drc").read_bytes() == b"abc"
    assert report["outputs"] == {"frames/0001.drc": 3, "job.glb": 5}
    assert read_report(destination) == report
    assert sorted(p.name for p in destination.iterdir()) == ["frames", "job.glb", REPORT_NAME]
    assert is_complete(destination, "k1") and not is_complete(destination, "other key")
    (destination / "job.glb").write_bytes(b"12")  # a truncated output is not complete
    assert not is_complete(destination, "k1")
    (destination / "job.glb").unlink()
    assert not is_complete(destination, "k1")


def test_interrupted_job_leaves_nothing(tmp_path):
    destination = tmp_path / "new" / "job"
    with pytest.raises(KeyboardInterrupt):
        with StagedOutput(destination) as staged:
            staged.write("frames/0001.drc", b"abc")
            raise KeyboardInterrupt
    assert not destination.exists()  # created by the job, empty again: removed


def test_rerun_replaces_outputs_and_drops_files_no_longer_produced(tmp_path):
    with StagedOutput(tmp_path) as staged:
        staged.write("frames/a.drc", b"old")
        staged.write("frames/b.drc", b"old")
        staged.commit({"job_key": "1"})
    (tmp_path / "mine.txt").write_text("the user's own file")
    with StagedOutput(tmp_path) as staged:
        staged.write("frames/a.drc", b"new")
        staged.commit({"job_key": "2"})
    assert (tmp_path / "frames/a.drc").read_bytes() == b"new"
    assert not (tmp_path / "frames/b.drc").exists() and (tmp_path / "mine.txt").exists()


def test_abandoned_staging_folders_are_removed(tmp_path):
    dead = tmp_path / ".meshik-partial-999999999-deadbeef"
    dead.mkdir()
    (dead / "half.drc").write_bytes(b"x")
    (dead / ".meshik-staging").write_bytes(b"")  # the marker every staging folder gets when made
    alive = tmp_path / f".meshik-partial-{os.getpid()}-cafe"
    alive.mkdir()
    (alive / ".meshik-staging").write_bytes(b"")
    users = tmp_path / ".meshik-partial-999999-notes"  # named like staging, but no run made it
    users.mkdir()
    (users / "notes.txt").write_text("mine")
    with StagedOutput(tmp_path) as staged:
        staged.commit({})
    assert not dead.exists() and alive.exists() and (users / "notes.txt").read_text() == "mine"


def test_unusable_destinations(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OutputError, match="output folder is a file"):
        check_writable(blocker)
    with pytest.raises(OutputError, match="cannot be created: .*file is a file"):
        StagedOutput(blocker / "sub" / "job")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]
