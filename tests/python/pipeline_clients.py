"""Real clients of the pipeline's outputs, for the tests: Google's draco_decoder (Debian `draco`)
and the Khronos glTF Validator (npm `gltf-validator`, installed by scripts/setup.sh node)."""
import json
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
VALIDATOR = ROOT / "node_modules" / "gltf-validator"


def draco_decoder() -> str:
    """Google's draco_decoder from the Debian package (not a copy bundled with a Python wheel)."""
    path = "/usr/bin/draco_decoder" if pathlib.Path("/usr/bin/draco_decoder").exists() else shutil.which("draco_decoder")
    if path is None:
        pytest.fail("draco_decoder not found: install the Debian package `draco` (scripts/setup.sh system)")
    return path


def validate_gltf(path: pathlib.Path) -> dict:
    """The Khronos glTF Validator's report (issues) for a .glb, run with node."""
    if not VALIDATOR.is_dir():
        pytest.fail(f"{VALIDATOR} missing: run scripts/setup.sh node (npm ci)")
    script = ("const fs = require('fs'); const v = require(process.argv[1]);"
              "v.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])), {maxIssues: 1000})"
              ".then(r => console.log(JSON.stringify(r.issues))).catch(e => { console.error(e); process.exit(2); });")
    done = subprocess.run(["node", "-e", script, str(VALIDATOR), str(path)], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def validate_and_check_no_errors(path: pathlib.Path) -> dict:
    """Validate a .glb and fail on any error or warning (infos about KHR_draco being unchecked are fine)."""
    issues = validate_gltf(path)
    problems = [m for m in issues["messages"] if m["severity"] <= 1]
    assert issues["numErrors"] == 0 and issues["numWarnings"] == 0, problems
    return issues


def decode_with_draco_decoder(drc: pathlib.Path, scratch: pathlib.Path):
    """(#V by 3 positions, #F by 3 triangles) of a .drc as Google's draco_decoder decodes it (via PLY)."""
    from meshik.inputs.meshio import load_mesh

    ply = scratch / (drc.stem + ".decoded.ply")
    subprocess.run([draco_decoder(), "-i", str(drc), "-o", str(ply)], check=True, capture_output=True)
    return load_mesh(ply)
