"""A fuzz of .glb files through `meshik info` (issue 23): mutated JSON, buffer views, meshopt and
Draco streams, each in a forked process of its own (a decoder's abort must not be mistaken for a pass).

Families:
- field mutations: every field MeshIK's readers use, in the meshopt, quantized and Draco .glb,
  set to a wrong type or an out-of-range value (before the fix: AttributeError / TypeError
  tracebacks, and SIGABRT from meshoptimizer's asserts for a byteStride of 3 or a count of 10);
- container damage: truncated files, a bad header, a JSON length past the end, 8 MB of nested
  arrays (RecursionError before), a primitive that is a list;
- stream damage: seeded byte flips inside the meshopt and Draco streams, where a decoder may
  still produce a mesh: those may print a summary (exit 0) or one error line, never more.
Every case: exit 1 with one line naming the file, no traceback, no signal death, input unchanged.
"""
import copy
import hashlib
import struct

import numpy as np
import pytest

from hostile_checks import assert_refused, run_forked
from meshik.export.glb_container import glb_bytes, split_glb
from meshik.pipeline import pose_job

VARIANTS = ("meshopt", "quantized", "draco")
BAD_VALUES = {"minus one": -1, "string": "x", "fraction": 2.5, "null": None, "list": [1], "object": {}, "2**64": 2 ** 64}


def _path(document, path):
    """The container and key at a '.'-separated path of keys and list indices in `document`."""
    parts = [int(p) if p.isdigit() else p for p in path.split(".")]
    node = document
    for part in parts[:-1]:
        node = node[part]
    return node, parts[-1]


def _meshopt_view(document, mode):
    """Index of the first buffer view compressed in `mode` (ATTRIBUTES or TRIANGLES)."""
    return next(i for i, v in enumerate(document["bufferViews"])
                if v.get("extensions", {}).get("EXT_meshopt_compression", {}).get("mode") == mode)


def _field_paths(variant):
    """The fields mutated in a .glb of `variant` ("ATTRIBUTES" stands for the index of the first
    meshopt view of that mode)."""
    paths = ["meshes.0.primitives.0", "accessors.0.count", "accessors.0.componentType", "accessors.0.type",
             "bufferViews.0.byteLength", "animations.0.samplers.0.input", "meshes.0.primitives.0.targets"]
    if variant == "draco":
        paths.append("meshes.0.primitives.0.extensions.KHR_draco_mesh_compression.bufferView")
    else:
        paths += ["nodes.0.scale", "meshes.0.primitives.0.attributes.POSITION"]
    if variant == "meshopt":
        paths += [f"bufferViews.ATTRIBUTES.extensions.EXT_meshopt_compression.{key}"
                  for key in ("byteStride", "count", "byteOffset", "mode")]
    return paths


MESHOPT_FIELDS = (("ATTRIBUTES", "byteStride", 3), ("TRIANGLES", "count", 10), ("ATTRIBUTES", "count", 10 ** 12),
                  ("TRIANGLES", "byteStride", 3), ("ATTRIBUTES", "byteLength", 10 ** 9))
CONTAINER_DAMAGE = ("primitive is a list", "truncated to half", "truncated to 30 bytes", "bad magic",
                    "JSON length past the end", "binary chunk cut")
RAW_JSON = {"nested arrays, 8 MB": b"[" * (4 << 20) + b"]" * (4 << 20), "JSON a list": b"[1, 2, 3]",
            "JSON not UTF-8": b'{"a": "\xff"}', "JSON with NaN": b'{"meshes": NaN}'}


def _case_names():
    """Every case's name, in a fixed order."""
    names = []
    for variant in VARIANTS:
        names += [f"{variant}: {path} = {label}" for path in _field_paths(variant) for label in BAD_VALUES]
        names += [f"{variant}: {damage}" for damage in CONTAINER_DAMAGE]
    names += [f"meshopt: {mode} {key} {value}" for mode, key, value in MESHOPT_FIELDS]
    return names + list(RAW_JSON)


def _mutations(document, binary, variant):
    """{case name: .glb bytes} of every mutation of one variant's document and binary chunk."""
    cases = {}
    for path in _field_paths(variant):
        for label, value in BAD_VALUES.items():
            changed = copy.deepcopy(document)
            node, key = _path(changed, path.replace("ATTRIBUTES", str(_meshopt_view(changed, "ATTRIBUTES")))
                              if "ATTRIBUTES" in path else path)
            node[key] = value
            cases[f"{variant}: {path} = {label}"] = glb_bytes(changed, binary)
    if variant == "meshopt":
        for mode, key, value in MESHOPT_FIELDS:
            changed = copy.deepcopy(document)
            changed["bufferViews"][_meshopt_view(changed, mode)]["extensions"]["EXT_meshopt_compression"][key] = value
            cases[f"meshopt: {mode} {key} {value}"] = glb_bytes(changed, binary)
    changed = copy.deepcopy(document)
    changed["meshes"][0]["primitives"] = [[changed["meshes"][0]["primitives"][0]]]
    data = glb_bytes(document, binary)
    damaged = {"primitive is a list": glb_bytes(changed, binary), "truncated to half": data[:len(data) // 2],
               "truncated to 30 bytes": data[:30], "bad magic": b"glTX" + data[4:],
               "JSON length past the end": data[:12] + struct.pack("<I", len(data)) + data[16:],
               "binary chunk cut": data[:-len(binary) // 2]}
    cases.update({f"{variant}: {damage}": damaged[damage] for damage in CONTAINER_DAMAGE})
    return cases


def _raw_glb(text):
    """A GLB container around JSON text given as bytes (no binary chunk)."""
    text += b" " * (-len(text) % 4)
    return struct.pack("<III", 0x46546C67, 2, 20 + len(text)) + struct.pack("<II", len(text), 0x4E4F534A) + text


@pytest.fixture(scope="module")
def glb_cases(tmp_path_factory, samples_dir):
    """{case: (path, sha256 before)} of every hostile .glb, and {case: Outcome} of `meshik info` on each."""
    folder = tmp_path_factory.mktemp("glb")
    cases = {}
    for variant in VARIANTS:
        pose_job(samples_dir / "bar" / "animation.json", folder / variant, formats="glb", glb=variant, quiet=True)
        document, binary = split_glb((folder / variant / "animation.glb").read_bytes())
        cases.update(_mutations(document, binary, variant))
    cases.update({name: _raw_glb(text) for name, text in RAW_JSON.items()})
    files = {}
    for number, (name, data) in enumerate(sorted(cases.items())):
        path = folder / "cases" / f"case_{number:03d}.glb"
        path.parent.mkdir(exist_ok=True)
        path.write_bytes(data)
        files[name] = (path, hashlib.sha256(data).hexdigest())
    outcomes = {name: run_forked(["info", path]) for name, (path, _) in files.items()}
    return files, outcomes


@pytest.mark.parametrize("case", _case_names())
def test_hostile_glb_is_one_line(glb_cases, case):
    files, outcomes = glb_cases
    path, digest = files[case]
    assert_refused(outcomes[case], str(path))
    assert hashlib.sha256(path.read_bytes()).hexdigest() == digest, "the input changed"


def test_stream_byte_flips_never_crash(tmp_path, samples_dir):
    """Seeded byte flips in the meshopt and Draco streams: a summary or one error line, never a
    signal death, a traceback or more lines."""
    rng = np.random.default_rng(2323)
    cases = {}
    for variant in ("meshopt", "draco"):
        pose_job(samples_dir / "bar" / "animation.json", tmp_path / variant, formats="glb", glb=variant, quiet=True)
        data = (tmp_path / variant / "animation.glb").read_bytes()
        json_length = struct.unpack_from("<I", data, 12)[0]
        start = 20 + json_length + 8
        for trial in range(12):
            mutated = bytearray(data)
            for offset in rng.integers(start, len(data), 4):
                mutated[offset] ^= int(rng.integers(1, 256))
            path = tmp_path / f"{variant}_{trial}.glb"
            path.write_bytes(bytes(mutated))
            cases[str(path)] = ["info", path]
    for name, outcome in {name: run_forked(args) for name, args in cases.items()}.items():
        lines = [line for line in outcome.stderr.splitlines() if line.strip()]
        assert outcome.returncode in (0, 1) and not outcome.timed_out, (name, outcome)
        assert "Traceback" not in outcome.stderr and len(lines) == (outcome.returncode == 1), (name, outcome.stderr)
        assert not outcome.left_behind
