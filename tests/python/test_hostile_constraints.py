"""Hostile constraint files and names (issue 23).

Families:
- frame names: a given name equal to another frame's default name, in either order (before:
  `validate` said OK and one 0002.drc was written for two frames);
- fps out of bounds (1e-300 gave key times [0, inf, inf], 1e308 [0, 0, 0]: invalid glTF);
- names with control characters in the constraint file's name and in a group's name: ESC, CSI,
  BEL, CR, LF, a C1 CSI and U+2028 (before: raw escape sequences on the terminal, a newline split
  the error line), through pose, info, blend and validate;
- 100,000 handle groups: read and refused (a vertex out of range) within 60 s (before: 45-94 s
  of quadratic duplicate-key and group-name searches just to validate);
- 20,000 frames with a .glb: refused before posing, naming the limit (before: not done after 120 s,
  the .glb step growing about quadratically).
"""
import json
import shutil
import time

import pytest

from hostile_checks import assert_refused, run_forked, run_in_process, tree_state


@pytest.fixture()
def work(tmp_path, samples_dir):
    """tmp_path/in: a copy of the bar sample."""
    shutil.copytree(samples_dir / "bar", tmp_path / "in")
    return tmp_path


def _edited(work, change, name="animation.json"):
    """The bar's constraint file after change(document), saved as in/<name>."""
    path = work / "in" / "animation.json"
    document = json.loads(path.read_text())
    document.pop("$schema", None)
    change(document)
    path.unlink()
    target = work / "in" / name
    target.write_text(json.dumps(document))
    return target


DOCUMENT_CASES = {
    "given name equals a later default name": (lambda d: d.update(frames=[{"name": "0002", "targets": {}}, {"targets": {}}]),
                                               'frames[1]: its default name "0002" is also the name of frames[0]'),
    "default name equals a later given name": (lambda d: d.update(frames=[{"targets": {}}, {"name": "0001"}]),
                                               'frames[1].name: "0001" is also the name of frames[0]'),
    "fps 1e-300": (lambda d: d.update(fps=1e-300), "fps: expected a frame rate from 0.001 to 10000"),
    "fps 1e308": (lambda d: d.update(fps=1e308), "fps: expected a frame rate from 0.001 to 10000"),
    "fps 0.0001": (lambda d: d.update(fps=0.0001), "fps: expected a frame rate"),
    "fps 100000": (lambda d: d.update(fps=100000), "fps: expected a frame rate"),
    "fps 1e300": (lambda d: d.update(fps=1e300), "fps: expected a frame rate"),
}


@pytest.mark.parametrize("command", ["pose", "info"])
@pytest.mark.parametrize("case", sorted(DOCUMENT_CASES))
def test_frame_names_and_fps(work, capsys, case, command):
    change, expected = DOCUMENT_CASES[case]
    path = _edited(work, change)
    args = ["pose", path, "--out", work / "out", "--quiet"] if command == "pose" else ["info", path]
    before = tree_state(work / "in")
    assert_refused(run_in_process(args, capsys), expected, work / "in", before, work, ("in",))


def test_validate_names_a_default_name_clash(work, capsys):
    path = _edited(work, lambda d: d.update(frames=[{"name": "0002", "targets": {}}, {"targets": {}}]))
    outcome = run_in_process(["validate", path], capsys)
    assert outcome.returncode == 1


HOSTILE_NAMES = {"ESC colour": "red\x1b[31mtext", "CSI clear screen": "x\x1b[2Jy", "BEL": "bell\x07",
                 "carriage return": "over\rwrite", "newline": "two\nlines", "C1 CSI": "c1\x9b31m",
                 "line separator": "ls\u2028x"}


@pytest.mark.parametrize("command", ["pose", "info", "blend"])
@pytest.mark.parametrize("case", sorted(HOSTILE_NAMES))
def test_control_characters_in_file_names_stay_escaped_on_one_line(work, case, command):
    """The constraint file named with control characters, its rest mesh missing: the one error line
    names it with the characters escaped (run forked: the escape must not reach the terminal)."""
    name = HOSTILE_NAMES[case]
    path = _edited(work, lambda d: d.update(rest="missing.obj"), name=f"{name}.json")
    args = {"pose": ["pose", path, "--out", work / "out"], "info": ["info", path],
            "blend": ["blend", path, "--weights", "0.5,0.5", "--out", work / "out.ply"]}[command]
    before = tree_state(work / "in")
    outcome = run_forked(args)
    escaped = name.encode("unicode_escape").decode("ascii")
    assert_refused(outcome, escaped, work / "in", before, work, ("in",))


@pytest.mark.parametrize("case", sorted(HOSTILE_NAMES))
def test_control_characters_in_a_group_name(work, case):
    name = HOSTILE_NAMES[case]
    path = _edited(work, lambda d: d["frames"][0]["targets"].update({name: {"translate": [0, 0, 0]}}))
    before = tree_state(work / "in")
    outcome = run_forked(["pose", path, "--out", work / "out", "--quiet"])
    assert_refused(outcome, "no handle group named", work / "in", before, work, ("in",))


def test_100000_handle_groups_are_read_in_linear_time(work, capsys):
    groups = {f"g{k}": [k] for k in range(100_000)}
    path = _edited(work, lambda d: d.update(handles=groups, frames=[{"targets": {"g99999": {"translate": [0, 0, 1]}}}]))
    before = tree_state(work / "in")
    start = time.monotonic()
    outcome = run_in_process(["pose", path, "--out", work / "out", "--quiet"], capsys)
    assert time.monotonic() - start < 60
    assert_refused(outcome, "is out of range", work / "in", before, work, ("in",))


def test_20000_frames_with_a_glb_are_refused_before_posing(work, capsys):
    frames = [{"name": f"f{k}", "targets": {}} for k in range(20_000)]
    path = _edited(work, lambda d: d.update(frames=frames))
    before = tree_state(work / "in")
    start = time.monotonic()
    outcome = run_in_process(["pose", path, "--out", work / "out", "--quiet", "--format", "glb"], capsys)
    assert time.monotonic() - start < 60
    assert_refused(outcome, "20000 frames is more than the 4096 one animated .glb holds", work / "in", before,
                   work, ("in",))
