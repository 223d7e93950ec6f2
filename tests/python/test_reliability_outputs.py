"""A run deletes only what it provably wrote, and every output name stays inside its folder.

Issue 12, defects 1 and 2: a report.json written by hand or by another tool must never make a run
delete files (inputs least of all); names that become paths cannot leave the output folder."""
import hashlib
import json
import shutil

import pytest

from meshik.errors import OutputError
from meshik.pipeline import pose_job
from meshik.outputs.staging import REPORT_NAME, StagedOutput


def test_a_stray_report_listing_other_files_deletes_nothing(tmp_path):
    destination = tmp_path / "job"
    destination.mkdir()
    (destination / "keep.txt").write_bytes(b"user data")
    (tmp_path / "outside.txt").write_bytes(b"user data")
    stray = {"outputs": {"keep.txt": 9, "../outside.txt": 9},
             "output_sha256": {"keep.txt": "0" * 64, "../outside.txt": "0" * 64}}
    (destination / REPORT_NAME).write_text(json.dumps(stray))
    with StagedOutput(destination) as staged:
        staged.write("frames/a.drc", b"new")
        staged.commit({"job_key": "k"})
    assert (destination / "keep.txt").read_bytes() == b"user data"
    assert (tmp_path / "outside.txt").read_bytes() == b"user data"


def test_an_earlier_output_changed_since_is_kept(tmp_path):
    with StagedOutput(tmp_path) as staged:
        staged.write("frames/a.drc", b"old a")
        staged.write("frames/b.drc", b"old b")
        staged.commit({"job_key": "k1"})
    (tmp_path / "frames/b.drc").write_bytes(b"edited by the user")
    with StagedOutput(tmp_path) as staged:
        staged.write("frames/c.drc", b"new c")
        staged.commit({"job_key": "k2"})
    assert not (tmp_path / "frames/a.drc").exists()  # ours, unchanged: removed
    assert (tmp_path / "frames/b.drc").read_bytes() == b"edited by the user"


def test_an_input_is_never_removed_even_with_a_matching_digest(tmp_path):
    with StagedOutput(tmp_path) as staged:
        staged.write("rest.obj", b"v 0 0 0\n")
        staged.commit({"job_key": "k1"})
    with StagedOutput(tmp_path) as staged:
        staged.write("frames/a.drc", b"x")
        staged.commit({"job_key": "k2"}, inputs=[tmp_path / "rest.obj"])
    assert (tmp_path / "rest.obj").read_bytes() == b"v 0 0 0\n"


@pytest.mark.parametrize("name", ["../escape.drc", "/abs/escape.drc", "frames/../../escape.drc", "..", ".", ""])
def test_an_output_name_outside_the_folder_is_refused(tmp_path, name):
    destination = tmp_path / "job"
    with StagedOutput(destination) as staged:
        with pytest.raises(OutputError, match="output file"):
            staged.write(name, b"x")
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_pose_with_a_hand_written_report_listing_its_inputs_deletes_nothing(samples_dir, tmp_path):
    work = tmp_path / "bar"
    shutil.copytree(samples_dir / "bar", work)
    before = {p.name: p.read_bytes() for p in work.iterdir()}
    listing = {name: len(data) for name, data in before.items()}
    digests = {name: hashlib.sha256(data).hexdigest() for name, data in before.items()}  # even the right digests
    (work / REPORT_NAME).write_text(json.dumps({"outputs": listing, "output_sha256": digests}))
    pose_job(work / "animation.json", work, formats="ply", quiet=True)
    for name, data in before.items():
        assert (work / name).read_bytes() == data, name
