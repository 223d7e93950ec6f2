"""The binary glTF (.glb) container, written and read by hand: a 12-byte header, a JSON chunk and a
binary chunk, buffer views appended 4-byte aligned, accessors read back with their component type.

MeshoptBinaryBuilder stores each buffer view compressed with EXT_meshopt_compression: the view
itself lives in a data-less fallback buffer (buffer 1) and its extension points at the encoded
bytes in the GLB's binary chunk (buffer 0).
"""
import functools
import json
import struct
from typing import Any, Callable, Dict, List, Tuple

import numpy as np

from meshik.export.gltf_checks import check_document

MESHOPT_EXTENSION = "EXT_meshopt_compression"
GLB_MAGIC, GLB_VERSION = 0x46546C67, 2
_CHUNK_JSON, _CHUNK_BIN = 0x4E4F534A, 0x004E4942
FLOAT, UNSIGNED_INT, UNSIGNED_SHORT, SHORT = 5126, 5125, 5123, 5122
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
COMPONENT_DTYPES = {5120: "<i1", 5121: "<u1", SHORT: "<i2", UNSIGNED_SHORT: "<u2", UNSIGNED_INT: "<u4", FLOAT: "<f4"}
COMPONENT_COUNTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def accessor(view, component_type: int, count: int, kind: str, values: np.ndarray, byte_offset: int = 0) -> Dict[str, Any]:
    """An accessor with min / max taken from `values` (count by components); no bufferView when view is None."""
    entry: Dict[str, Any] = {"componentType": component_type, "count": int(count), "type": kind,
                             "min": values.min(axis=0).astype(float).tolist(), "max": values.max(axis=0).astype(float).tolist()}
    if view is not None:
        entry["bufferView"] = view
        if byte_offset:
            entry["byteOffset"] = int(byte_offset)
    return entry


class BinaryBuilder:
    """The binary chunk under construction: appends 4-byte-aligned buffer views."""

    def __init__(self):
        self.data = bytearray()
        self.views: List[Dict[str, Any]] = []

    def view(self, payload: bytes, stride: int = 0, target: int = 0) -> int:
        """Append `payload` as a new buffer view; returns its index."""
        self.data += b"\0" * (-len(self.data) % 4)
        entry: Dict[str, Any] = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if stride:
            entry["byteStride"] = stride
        if target:
            entry["target"] = target
        self.data += payload
        self.views.append(entry)
        return len(self.views) - 1

    def index_view(self, indices: np.ndarray, vertex_count: int) -> Tuple[int, int]:
        """Append a triangle list (3 #F indices) as the smallest unsigned type; (view, componentType)."""
        small = vertex_count <= 2 ** 16
        payload = np.asarray(indices, dtype="<u2" if small else "<u4").tobytes()
        return self.view(payload, target=ELEMENT_ARRAY_BUFFER), UNSIGNED_SHORT if small else UNSIGNED_INT

    def buffers(self) -> List[Dict[str, Any]]:
        """The document's "buffers": the binary chunk."""
        return [{"byteLength": len(self.data)}]


class MeshoptBinaryBuilder(BinaryBuilder):
    """Buffer views compressed with EXT_meshopt_compression (ATTRIBUTES for vertex and animation
    streams, TRIANGLES for indices), decoded into a fallback buffer that holds no data."""

    def __init__(self):
        super().__init__()
        self.fallback_length = 0

    def view(self, payload: bytes, stride: int = 0, target: int = 0) -> int:
        """Append `payload` (elements of `stride` bytes, 4 when 0) compressed; returns the view's index."""
        from meshik import _meshopt

        element = stride or 4
        rows = np.frombuffer(payload, dtype=np.uint8).reshape(-1, element)
        return self._compressed(_meshopt.encode_vertex_buffer(np.ascontiguousarray(rows)), len(payload), element,
                                len(rows), "ATTRIBUTES", stride, target)

    def index_view(self, indices: np.ndarray, vertex_count: int) -> Tuple[int, int]:
        """Append a triangle list (3 #F indices) compressed in TRIANGLES mode; (view, componentType)."""
        from meshik import _meshopt

        small = vertex_count <= 2 ** 16
        element = 2 if small else 4
        encoded = _meshopt.encode_index_buffer(np.ascontiguousarray(indices, dtype=np.uint32), vertex_count)
        view = self._compressed(encoded, len(indices) * element, element, len(indices), "TRIANGLES", 0, ELEMENT_ARRAY_BUFFER)
        return view, UNSIGNED_SHORT if small else UNSIGNED_INT

    def _compressed(self, encoded: bytes, length: int, element: int, count: int, mode: str, stride: int, target: int) -> int:
        """Append `encoded` to the chunk and a view of `length` decoded bytes in the fallback buffer."""
        self.data += b"\0" * (-len(self.data) % 4)
        self.fallback_length += -self.fallback_length % 4
        entry: Dict[str, Any] = {"buffer": 1, "byteOffset": self.fallback_length, "byteLength": length,
                                 "extensions": {MESHOPT_EXTENSION: {"buffer": 0, "byteOffset": len(self.data),
                                                                    "byteLength": len(encoded), "byteStride": element,
                                                                    "count": count, "mode": mode}}}
        if stride:
            entry["byteStride"] = stride
        if target:
            entry["target"] = target
        self.data += encoded
        self.fallback_length += length
        self.views.append(entry)
        return len(self.views) - 1

    def buffers(self) -> List[Dict[str, Any]]:
        """The binary chunk and the fallback buffer the compressed views decode into."""
        return [{"byteLength": len(self.data)},
                {"byteLength": self.fallback_length, "extensions": {MESHOPT_EXTENSION: {"fallback": True}}}]


def glb_bytes(document: Dict[str, Any], binary: bytes) -> bytes:
    """A GLB container: header, JSON chunk (space-padded), BIN chunk (zero-padded)."""
    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<III", GLB_MAGIC, GLB_VERSION, total) + struct.pack("<II", len(text), _CHUNK_JSON) + text
            + struct.pack("<II", len(binary), _CHUNK_BIN) + binary)


def split_glb(data: bytes) -> Tuple[Dict[str, Any], bytes]:
    """(JSON document, binary chunk) of GLB bytes; ValueError when the container is malformed or a
    field MeshIK's readers use is not what they need (meshik.export.gltf_checks)."""
    if len(data) < 20:
        raise ValueError("not a GLB file: too short")
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != GLB_MAGIC or version != GLB_VERSION or length != len(data):
        raise ValueError("not a GLB 2.0 file (bad header)")
    json_length, json_type = struct.unpack_from("<II", data, 12)
    if json_type != _CHUNK_JSON:
        raise ValueError("GLB: the first chunk is not JSON")
    if 20 + json_length > len(data):
        raise ValueError(f"GLB: the JSON chunk's length {json_length} runs past the file's end")
    try:
        document = json.loads(data[20:20 + json_length])
    except RecursionError:
        raise ValueError("GLB: the JSON chunk is nested too deeply") from None
    offset = 20 + json_length
    binary = b""
    if offset + 8 <= len(data):
        binary_length, binary_type = struct.unpack_from("<II", data, offset)
        if binary_type == _CHUNK_BIN:
            binary = data[offset + 8:offset + 8 + binary_length]
    check_document(document, len(binary))
    return document, binary


def view_reader(document: Dict[str, Any], binary: bytes) -> Callable[[int], bytes]:
    """A function giving the (decoded) bytes of buffer view `index`; buffer 0 is the GLB binary
    chunk, views with EXT_meshopt_compression are decoded from it, once each (every morph target's
    accessor lies in one shared view: decoding it per accessor made reading quadratic in the frames)."""
    @functools.lru_cache(maxsize=None)
    def view_bytes(index: int) -> bytes:
        view = document["bufferViews"][index]
        compressed = view.get("extensions", {}).get(MESHOPT_EXTENSION)
        if compressed is None:
            start = view.get("byteOffset", 0)
            return binary[start:start + view["byteLength"]]
        from meshik import _meshopt

        start = compressed.get("byteOffset", 0)
        encoded = binary[start:start + compressed["byteLength"]]
        if compressed["mode"] == "TRIANGLES":
            indices = _meshopt.decode_index_buffer(encoded, compressed["count"])
            return indices.astype("<u2" if compressed["byteStride"] == 2 else "<u4").tobytes()
        return _meshopt.decode_vertex_buffer(encoded, compressed["count"], compressed["byteStride"]).tobytes()
    return view_bytes


def read_accessor(document: Dict[str, Any], view_bytes: Callable[[int], bytes], index: int) -> np.ndarray:
    """Accessor `index` as count by components, in its stored component type (no normalization),
    honouring byteStride; view_bytes as from view_reader."""
    entry = document["accessors"][index]
    components = COMPONENT_COUNTS[entry["type"]]
    dtype = np.dtype(COMPONENT_DTYPES[entry["componentType"]])
    stride = document["bufferViews"][entry["bufferView"]].get("byteStride", dtype.itemsize * components)
    payload = view_bytes(entry["bufferView"])
    return np.ndarray((entry["count"], components), dtype=dtype, buffer=payload, offset=entry.get("byteOffset", 0),
                      strides=(stride, dtype.itemsize)).copy()
