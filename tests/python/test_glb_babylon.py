"""Babylon.js plays every .glb variant right: its NullEngine and glTF loader (npm @babylonjs/core and
@babylonjs/loaders, pinned in package.json) load each file of glb_variants in Node
(tests/node/babylon_glb.mjs), the animation group is moved to each key, and the mesh's positions
there (morph targets mixed by Babylon) are within the variant's error bound of the solver's frame,
vertex by vertex (Babylon keeps the file's vertex order, whose ids the file carries); its weights
at each key are the file's, and its default weights the first key's."""
import json
import subprocess

import numpy as np
import pytest

from glb_variants import LABELS, glb_cases  # noqa: F401 - glb_cases is a fixture
from meshik.export.glb_reader import read_animation_glb
from meshik.export.glb_layout import rows_of_ids
from pipeline_clients import ROOT

PLAYER = ROOT / "tests" / "node" / "babylon_glb.mjs"


@pytest.fixture(scope="module")
def played(glb_cases, tmp_path_factory):
    """{label: (GlbCase, Babylon's summary, #frames by #V by 3 positions or None)}: every file in one
    Node process."""
    scratch = tmp_path_factory.mktemp("babylon")
    labels = sorted(glb_cases)
    manifest = [[str(glb_cases[label].glb), str(scratch / f"{index}.bin")] for index, label in enumerate(labels)]
    (scratch / "manifest.json").write_text(json.dumps(manifest))
    done = subprocess.run(["node", str(PLAYER), str(scratch / "manifest.json")], capture_output=True, text=True,
                          cwd=ROOT, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    summaries = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    assert [s["glb"] for s in summaries] == [glb for glb, _ in manifest]
    played = {}
    for label, summary, (_, raw) in zip(labels, summaries, manifest):
        positions = np.fromfile(raw, dtype="<f8").reshape(summary["frames"], summary["vertices"], 3) \
            if summary["loaded"] else None
        played[label] = (glb_cases[label], summary, positions)
    return played


@pytest.mark.parametrize("label", LABELS)
def test_babylon_plays_every_key_within_the_bound(played, label):
    if label not in played:
        pytest.skip("the horse gallop is not in ../shared/data")
    case, summary, positions = played[label]
    assert summary["loaded"], summary["error"]
    assert any(reader.startswith("Babylon.js") for reader in case.readers["opens_in"])
    animation = read_animation_glb(case.glb.read_bytes())
    expected = case.frames[:, rows_of_ids(case.ids, animation.vertex_ids)]
    assert positions.shape == expected.shape
    error = np.linalg.norm(positions - expected, axis=2).max()
    assert error <= case.bound(), (error, case.bound())
    np.testing.assert_allclose(summary["times"], animation.times, atol=1e-6)
    np.testing.assert_allclose(summary["weightsAtKeys"], animation.weights, atol=1e-6)
    assert 0 <= np.min(summary["weightsAtKeys"]) and np.max(summary["weightsAtKeys"]) <= 1
    np.testing.assert_allclose(summary["defaultWeights"], animation.weights[0], atol=1e-6)
