"""Outputs that would land on inputs, and the output folder's own names (issue 23).

Families:
- an output path that is an input, by name, by real path (a link) or by inode (a hard link):
  `pose d/report.json --out d` (before: exit 0, the input replaced by the run's report), a frame
  named like an example under frames/ with --format obj, blend --out onto an example, a batch whose
  report would replace a constraint file, a hard link of the constraint file at the report's place;
- names the run must not touch: a user's folder named like stale staging survives;
- blend's own output: an unknown extension named as given (before: the staging file's name).
Each is refused before anything is written: exit 1, one line, inputs unchanged.
"""
import json
import os
import shutil

import pytest

from hostile_checks import assert_refused, run_forked, run_meshik, tree_state
from meshik.cli import main


@pytest.fixture()
def work(tmp_path, samples_dir):
    """tmp_path/in: a copy of the bar sample."""
    shutil.copytree(samples_dir / "bar", tmp_path / "in")
    return tmp_path


def _report_named_input(work):
    bar = work / "in"
    (bar / "animation.json").rename(bar / "report.json")
    return ["pose", bar / "report.json", "--out", bar, "--quiet", "--format", "ply"], "report.json: this output would replace"


def _frame_named_like_an_example(work):
    bar = work / "in"
    (bar / "frames").mkdir()
    document = json.loads((bar / "animation.json").read_text())
    for name in ("example_1", "example_2"):
        shutil.move(bar / f"{name}.obj", bar / "frames" / f"{name}.obj")
    document["examples"] = ["frames/example_1.obj", "frames/example_2.obj"]
    document["frames"][0]["name"] = "example_1"
    (bar / "animation.json").write_text(json.dumps(document))
    return ["pose", bar / "animation.json", "--out", bar, "--quiet", "--format", "obj"], "frames/example_1.obj: this output"


def _hard_link_at_the_report(work):
    (work / "out").mkdir()
    os.link(work / "in" / "animation.json", work / "out" / "report.json")
    return ["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet"], "would replace the input"


def _symlink_at_a_frame(work):
    (work / "out" / "frames").mkdir(parents=True)
    (work / "out" / "frames" / "0001.drc").symlink_to(work / "in" / "rest.obj")
    return ["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet"], "rest.obj"


def _blend_onto_an_example(work):
    bar = work / "in"
    return ["blend", bar / "rest.obj", bar / "example_1.obj", bar / "example_2.obj", "--weights", "0.5,0.5",
            "--out", bar / "example_2.obj"], "example_2.obj: this output would replace the input"


def _blend_unknown_format(work):
    bar = work / "in"
    return ["blend", bar / "animation.json", "--weights", "0.5,0.5", "--out", work / "out" / "x.notaformat"], \
        "x.notaformat: unknown output format '.notaformat'"


def _batch_report_is_the_input(work):
    bar = work / "in"
    (bar / "animation.json").rename(bar / "batch-report.json")
    return ["batch", bar / "batch-report.json", "--out", bar, "--quiet", "--jobs", "1"], "batch-report.json: this output"


CASES = {"pose report.json --out its folder": _report_named_input,
         "frame named like an example, --format obj": _frame_named_like_an_example,
         "hard link of the input at report.json": _hard_link_at_the_report,
         "symbolic link to the rest at a frame's name": _symlink_at_a_frame,
         "blend --out onto an example": _blend_onto_an_example,
         "blend --out x.notaformat": _blend_unknown_format,
         "batch report would replace the constraint file": _batch_report_is_the_input}


@pytest.mark.parametrize("case", sorted(CASES))
def test_outputs_never_replace_inputs(work, case):
    args, expected = CASES[case](work)
    before = tree_state(work / "in")
    out_before = tree_state(work / "out") if (work / "out").exists() else None
    assert_refused(run_forked(args), expected, work / "in", before, work)
    if out_before is not None:
        assert tree_state(work / "out") == out_before


def test_batch_job_report_is_the_input_folder(work):
    """`batch D/report/report.json --out D`: the job folder D/report would get the input's name."""
    (work / "in" / "report").mkdir()
    document = json.loads((work / "in" / "animation.json").read_text())
    document["rest"] = "../rest.obj"
    document["examples"] = ["../example_1.obj", "../example_2.obj"]
    (work / "in" / "report" / "report.json").write_text(json.dumps(document))
    before = tree_state(work / "in")
    outcome = run_forked(["batch", work / "in" / "report" / "report.json", "--out", work / "in", "--quiet", "--jobs", "1"],
                         timeout=180)
    assert_refused(outcome, "report.json: this output would replace the input", work / "in", before, work)


def test_a_users_folder_named_like_staging_survives(work, capsys):
    notes = work / "out" / ".meshik-partial-999999-notes"
    notes.mkdir(parents=True)
    (notes / "mine.txt").write_text("keep me")
    assert main(["pose", str(work / "in" / "animation.json"), "--out", str(work / "out"), "--quiet"]) == 0
    assert (notes / "mine.txt").read_text() == "keep me"
    assert not [p for p in (work / "out").iterdir() if p.name.startswith(".meshik-partial-") and p != notes]


def test_a_frame_that_cannot_be_moved_in_is_named(work):
    """A folder of the user's at a frame's final name: the commit stops naming that file (before:
    a message naming no file)."""
    blocker = work / "out" / "frames" / "0001.drc"
    blocker.mkdir(parents=True)
    (blocker / "keep.txt").write_text("mine")
    before = tree_state(work / "in")
    # A new process, not a fork: this run poses, and a forked child's first OpenMP region deadlocks
    # when the test process has already used OpenMP (GNU libgomp is not fork-safe).
    outcome = run_meshik(["pose", work / "in" / "animation.json", "--out", work / "out", "--quiet", "--format", "drc"])
    assert_refused(outcome, "frames/0001.drc: cannot move this output into place", work / "in", before, work)
    assert (blocker / "keep.txt").read_text() == "mine"
