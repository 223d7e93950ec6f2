"""The output preview: `make demo`'s index.html served by `meshik view` (meshik.preview.server) opened in
headless Chromium (Debian's `chromium` through playwright-core, tests/node/preview_check.mjs): it
loads with no console error, the animation plays, the slider shows a chosen frame, and the contact
sheet and report are beside it; the server gives nothing outside the folder and its fixed list."""
import json
import shutil
import subprocess
import threading

import numpy as np
import pytest

from meshik import demo
from meshik.export.glb_reader import read_animation_glb
from meshik.preview.server import open_request, preview_server
from meshik.preview.site import VENDOR_FILES
from pipeline_clients import ROOT

CHECK = ROOT / "tests" / "node" / "preview_check.mjs"
CHROMIUM = "/usr/bin/chromium"


@pytest.fixture(scope="module")
def demo_output(tmp_path_factory):
    """A folder written by the demo (three samples, contact sheets, index.html)."""
    out = tmp_path_factory.mktemp("demo")
    assert demo.main(["--out", str(out)]) == 0
    return out


@pytest.fixture
def served(demo_output):
    """The base URL of `meshik view`'s server on the demo folder (any free port), serving in a thread."""
    server = preview_server(demo_output, port=0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        host, port = server.server_address[:2]
        yield f"http://{host}:{port}/"
    finally:
        server.shutdown()
        server.server_close()


def test_demo_writes_a_self_contained_offline_page(demo_output):
    page = (demo_output / "index.html").read_text()
    manifest = json.loads(page.split('id="manifest">')[1].split("</script>")[0])
    assert [job["name"] for job in manifest["jobs"]] == ["bar", "flag", "limb"]
    for job in manifest["jobs"]:
        assert (demo_output / job["glb"]).is_file() and (demo_output / job["sheet"]).is_file()
    for relative in VENDOR_FILES:
        assert (demo_output / "viewer" / "vendor" / relative).is_file(), relative
    # nothing is fetched from elsewhere: no absolute URL in the page or the app
    assert "://" not in page and "://" not in (demo_output / "viewer" / "app.js").read_text()


@pytest.mark.skipif(not shutil.which(CHROMIUM), reason="Debian's chromium is not installed (scripts/setup.sh system)")
def test_page_plays_the_animation_and_the_slider_picks_a_frame(served, demo_output, tmp_path):
    frame = 7
    done = subprocess.run(["node", str(CHECK), served, str(frame), str(tmp_path)], capture_output=True, text=True,
                          cwd=ROOT, timeout=240)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout)
    assert seen["consoleErrors"] == [] and seen["pageErrors"] == [] and seen["failedRequests"] == [], seen
    assert seen["viewerError"] is None
    report = json.loads((demo_output / "bar" / "report.json").read_text())  # the first job shown
    assert seen["frameCount"] == report["frame_count"]
    # the camera frames the whole animation: the box spans every frame's vertices, and no more
    animation = read_animation_glb((demo_output / "bar" / "animation.glb").read_bytes())
    low, high = animation.frames.min(axis=(0, 1)), animation.frames.max(axis=(0, 1))
    np.testing.assert_allclose(seen["framedBox"], [low, high], atol=1e-5 * np.linalg.norm(high - low))
    assert seen["playedDiffers"], "two screenshots 0.7 s apart are the same: the animation does not play"
    assert seen["sliderFrame"] == frame and not seen["playingAfterSlider"]
    # the mesh mixes its targets with the file's weights of the slider's key
    expected = animation.weights[frame]
    np.testing.assert_allclose(seen["influencesAtSlider"], expected, atol=1e-5)
    assert seen["sheetLoaded"] and '"compressed_outputs"' in seen["reportText"]


def test_server_refuses_paths_outside_the_folder(demo_output, tmp_path):
    outside = tmp_path / "secret.txt"
    outside.write_text("no")
    (demo_output / "link.txt").symlink_to(outside)
    (demo_output / "linked").symlink_to(tmp_path)
    try:
        for url in ("/../secret.txt", "/%2e%2e/secret.txt", "/bar/../../secret.txt", "/link.txt", "/viewer/../bar",
                    "/viewer/vendor/three/package.json", "/viewer/vendor/../../../etc/passwd", "/missing.glb",
                    "/linked/secret.txt", "/bar", "/bar/", "/%00"):
            assert open_request(demo_output, url) is None, url
    finally:
        (demo_output / "link.txt").unlink()
        (demo_output / "linked").unlink()
    stream, size, suffix = open_request(demo_output, "/bar/report.json?x=1")
    with stream:
        assert stream.read() == (demo_output / "bar" / "report.json").read_bytes() and suffix == ".json"
    stream, size, suffix = open_request(demo_output, "/")
    assert suffix == ".html" and "bar/animation.glb" in stream.read().decode()
    assert open_request(demo_output, "/viewer/vendor/three/build/three.module.js")[1] > 0
