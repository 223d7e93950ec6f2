"""One binary glTF (.glb) per animation: a Draco-compressed base mesh, the frames as morph targets.

Layout: one mesh with one primitive whose POSITION, indices and "_ORIGINAL_ID" live in a
KHR_draco_mesh_compression buffer (the rest pose); one morph target per frame (KHR_draco does not
compress morph targets) holding frame - decoded rest, in Draco's decoded vertex order, so that
rest + target k reproduces frame k to float32 precision; one animation that steps the morph
weights through the frames at the file's frame rate (linear in between). The animation's
#frames x #frames weights are one sparse accessor (zero but for each key's own target), so the
file and the writer's memory grow linearly with the frames. Written by hand: a GLB is a 12-byte
header, a JSON chunk and a binary chunk.
"""
import json
import struct
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from meshik.export_draco import ID_ATTRIBUTE, QuantizationGrid, decode, encode_frame

DRACO_EXTENSION = "KHR_draco_mesh_compression"
ID_SEMANTIC = "_ORIGINAL_ID"
_GLB_MAGIC, _GLB_VERSION = 0x46546C67, 2
_CHUNK_JSON, _CHUNK_BIN = 0x4E4F534A, 0x004E4942
_FLOAT, _UNSIGNED_INT = 5126, 5125
_ARRAY_BUFFER = 34962
_FLOAT_EXACT_INTEGERS = 2 ** 24
_GLB_MAX_BYTES = 2 ** 32 - 1          # the GLB header's 32-bit length
MAX_GLB_FRAMES = 2 ** 16 - 1         # sparse weight indices (uint32) address #frames squared values


def glb_size_problem(frames: int, vertices: int) -> Optional[str]:
    """Why an animation of `frames` frames of `vertices` vertices cannot be one .glb, or None.

    Known before posing: the morph targets alone take frames x vertices x 12 bytes.
    """
    if frames > MAX_GLB_FRAMES:
        return f"{frames} frames is more than the {MAX_GLB_FRAMES} one animated .glb can hold"
    estimate = frames * (vertices * 12 + 12) + vertices * 16
    if estimate > _GLB_MAX_BYTES:
        return (f"{frames} frames of {vertices} vertices need about {estimate / 2 ** 30:.1f} GiB of morph targets, "
                "more than the 4 GiB a .glb file can hold")
    return None


def animation_glb(rest: np.ndarray, faces: np.ndarray, frames: np.ndarray, frame_names: Sequence[str],
                  vertex_ids: np.ndarray, grid: QuantizationGrid, fps: float, name: str, generator: str) -> bytes:
    """GLB bytes of an animation.

    rest: #V by 3 base positions; faces: #F by 3; frames: #frames by #V by 3 positions;
    vertex_ids: #V ids stored per vertex (e.g. the full-resolution vertex ids); grid: the Draco
    quantisation of the base mesh; fps: frames per second of the animation.
    """
    if len(vertex_ids) and int(np.max(vertex_ids)) >= _FLOAT_EXACT_INTEGERS:
        raise ValueError(f"vertex ids up to {_FLOAT_EXACT_INTEGERS} fit a glTF float attribute; got {int(np.max(vertex_ids))}")
    draco = encode_frame(rest, faces, vertex_ids, grid, id_type=np.float32)
    decoded = decode(draco)
    local = _local_indices(np.asarray(vertex_ids), decoded.vertex_ids)
    base = decoded.vertices.astype(np.float32)
    targets = (np.asarray(frames, dtype=np.float64)[:, local] - base.astype(np.float64)).astype(np.float32)
    problem = glb_size_problem(len(frames), len(base))
    if problem:
        raise ValueError(problem)
    times = (np.arange(len(frames)) / fps).astype(np.float32)
    keys = np.arange(len(frames), dtype=np.uint32)

    binary = _BinaryBuilder()
    draco_view = binary.view(draco)
    targets_view = binary.view(targets.tobytes(), stride=12, target=_ARRAY_BUFFER)
    times_view = binary.view(times.tobytes())
    weight_indices_view = binary.view((keys * (len(frames) + 1)).tobytes())  # key k sets target k
    weight_values_view = binary.view(np.ones(len(frames), dtype=np.float32).tobytes())

    count = len(base)
    accessors: List[Dict[str, Any]] = [
        _accessor(None, _FLOAT, count, "VEC3", base),
        {"componentType": _UNSIGNED_INT, "count": int(decoded.faces.size), "type": "SCALAR"},
        _accessor(None, _FLOAT, count, "SCALAR", decoded.vertex_ids.reshape(-1, 1).astype(np.float32)),
    ]
    for k, target in enumerate(targets):
        accessors.append(_accessor(targets_view, _FLOAT, count, "VEC3", target, byte_offset=k * count * 12))
    times_accessor = len(accessors)
    accessors.append(_accessor(times_view, _FLOAT, len(times), "SCALAR", times.reshape(-1, 1)))
    accessors.append({"componentType": _FLOAT, "count": len(frames) ** 2, "type": "SCALAR",
                      "sparse": {"count": len(frames),
                                 "indices": {"bufferView": weight_indices_view, "componentType": _UNSIGNED_INT},
                                 "values": {"bufferView": weight_values_view}}})

    primitive = {
        "attributes": {"POSITION": 0, ID_SEMANTIC: 2},
        "indices": 1,
        "mode": 4,
        "targets": [{"POSITION": 3 + k} for k in range(len(frames))],
        "extensions": {DRACO_EXTENSION: {"bufferView": draco_view, "attributes": {
            "POSITION": decoded.attribute_ids["POSITION"], ID_SEMANTIC: decoded.attribute_ids[ID_ATTRIBUTE]}}},
    }
    document = {
        "asset": {"version": "2.0", "generator": generator},
        "extensionsUsed": [DRACO_EXTENSION],
        "extensionsRequired": [DRACO_EXTENSION],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": name}],
        "meshes": [{"name": name, "primitives": [primitive], "weights": [0.0] * len(frames),
                    "extras": {"targetNames": list(frame_names)}}],
        "animations": [{"name": name, "samplers": [{"input": times_accessor, "output": times_accessor + 1,
                                                    "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}],
        "accessors": accessors,
        "bufferViews": binary.views,
        "buffers": [{"byteLength": len(binary.data)}],
    }
    return _glb_bytes(document, bytes(binary.data))


def _local_indices(vertex_ids: np.ndarray, decoded_ids: np.ndarray) -> np.ndarray:
    """For each decoded vertex, the row of `vertex_ids` (distinct ids) that carries its id."""
    order = np.argsort(vertex_ids)
    return order[np.searchsorted(vertex_ids[order], decoded_ids)]


def _accessor(view, component_type: int, count: int, kind: str, values: np.ndarray, byte_offset: int = 0) -> Dict[str, Any]:
    """An accessor with min / max taken from `values` (count by components); no bufferView when view is None."""
    accessor: Dict[str, Any] = {"componentType": component_type, "count": int(count), "type": kind,
                                "min": values.min(axis=0).astype(float).tolist(), "max": values.max(axis=0).astype(float).tolist()}
    if view is not None:
        accessor["bufferView"] = view
        if byte_offset:
            accessor["byteOffset"] = int(byte_offset)
    return accessor


class _BinaryBuilder:
    """The binary chunk under construction: appends 4-byte-aligned buffer views."""

    def __init__(self):
        self.data = bytearray()
        self.views: List[Dict[str, Any]] = []

    def view(self, payload: bytes, stride: int = 0, target: int = 0) -> int:
        """Append `payload` as a new buffer view; returns its index."""
        self.data += b"\0" * (-len(self.data) % 4)
        view: Dict[str, Any] = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if stride:
            view["byteStride"] = stride
        if target:
            view["target"] = target
        self.data += payload
        self.views.append(view)
        return len(self.views) - 1


def _glb_bytes(document: Dict[str, Any], binary: bytes) -> bytes:
    """A GLB container: header, JSON chunk (space-padded), BIN chunk (zero-padded)."""
    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<III", _GLB_MAGIC, _GLB_VERSION, total) + struct.pack("<II", len(text), _CHUNK_JSON) + text
            + struct.pack("<II", len(binary), _CHUNK_BIN) + binary)


@dataclass(frozen=True)
class AnimationGlb:
    """What read_animation_glb finds in a MeshIK .glb.

    rest: #D by 3 decoded base positions (Draco order); faces: #F by 3; vertex_ids: #D;
    frames: #frames by #D by 3 (rest + morph target k); frame_names; times: #frames seconds.
    """
    rest: np.ndarray
    faces: np.ndarray
    vertex_ids: np.ndarray
    frames: np.ndarray
    frame_names: Tuple[str, ...]
    times: np.ndarray


def read_animation_glb(data: bytes) -> AnimationGlb:
    """Parse a .glb written by animation_glb (first mesh, first primitive). Raises ValueError."""
    document, binary = _split_glb(data)
    primitive = document["meshes"][0]["primitives"][0]
    draco = primitive["extensions"][DRACO_EXTENSION]
    decoded = decode(_view_bytes(document, binary, draco["bufferView"]))
    base = decoded.vertices.astype(np.float32)
    frames = np.stack([base + _read_accessor(document, binary, target["POSITION"]) for target in primitive["targets"]])
    sampler = document["animations"][0]["samplers"][0]
    return AnimationGlb(rest=decoded.vertices, faces=decoded.faces, vertex_ids=decoded.vertex_ids,
                        frames=frames.astype(np.float64),
                        frame_names=tuple(document["meshes"][0].get("extras", {}).get("targetNames", [])),
                        times=_read_accessor(document, binary, sampler["input"]).reshape(-1))


def _split_glb(data: bytes) -> Tuple[Dict[str, Any], bytes]:
    """(JSON document, binary chunk) of GLB bytes; ValueError when the container is malformed."""
    if len(data) < 20:
        raise ValueError("not a GLB file: too short")
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != _GLB_MAGIC or version != _GLB_VERSION or length != len(data):
        raise ValueError("not a GLB 2.0 file (bad header)")
    json_length, json_type = struct.unpack_from("<II", data, 12)
    if json_type != _CHUNK_JSON:
        raise ValueError("GLB: the first chunk is not JSON")
    document = json.loads(data[20:20 + json_length])
    offset = 20 + json_length
    binary = b""
    if offset + 8 <= len(data):
        binary_length, binary_type = struct.unpack_from("<II", data, offset)
        if binary_type == _CHUNK_BIN:
            binary = data[offset + 8:offset + 8 + binary_length]
    return document, binary


def _view_bytes(document: Dict[str, Any], binary: bytes, index: int) -> bytes:
    """The bytes of buffer view `index` (buffer 0 is the GLB binary chunk)."""
    view = document["bufferViews"][index]
    start = view.get("byteOffset", 0)
    return binary[start:start + view["byteLength"]]


def _read_accessor(document: Dict[str, Any], binary: bytes, index: int) -> np.ndarray:
    """A float accessor (SCALAR or VEC3) as count by components float32, honouring byteStride."""
    accessor = document["accessors"][index]
    components = {"SCALAR": 1, "VEC3": 3}[accessor["type"]]
    view = document["bufferViews"][accessor["bufferView"]]
    stride = view.get("byteStride", 4 * components)
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    return np.ndarray((accessor["count"], components), dtype="<f4", buffer=binary, offset=start, strides=(stride, 4)).copy()
