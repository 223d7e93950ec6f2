"""Draco (.drc) encoding of animation frames: edgebreaker, one quantisation grid for all frames.

Edgebreaker reorders vertices (the same way for every frame, since all frames share their
triangles), so each file carries a generic attribute "original_id" (uint32) with the vertex id
of the input mesh for every decoded vertex. All frames of an animation are quantised on one grid
(origin and range of the whole animation's bounding cube), so a vertex that does not move
decodes to the same position in every frame.
"""
from dataclasses import dataclass
from typing import Dict, Optional, Tuple

import numpy as np

ID_ATTRIBUTE = "original_id"
DEFAULT_QUANTIZATION_BITS = 14
DEFAULT_COMPRESSION_LEVEL = 7   # DracoPy level 1..10 selects edgebreaker; 0 would be sequential
_HEADER_METHOD_BYTE = 8          # "DRACO", major, minor, encoder type, then the method byte
EDGEBREAKER = 1


@dataclass(frozen=True)
class QuantizationGrid:
    """A Draco position grid: `bits` per coordinate over the cube [origin, origin + range]^3."""
    origin: Tuple[float, float, float]
    range: float
    bits: int

    @property
    def step(self) -> float:
        """Spacing of the grid: a decoded coordinate is within step / 2 of the encoded one."""
        return self.range / (2 ** self.bits - 1)


def animation_grid(frames: np.ndarray, bits: int = DEFAULT_QUANTIZATION_BITS) -> QuantizationGrid:
    """The grid covering every position of every frame (#frames by #V by 3, or #V by 3)."""
    points = np.asarray(frames, dtype=np.float64).reshape(-1, 3)
    low, high = points.min(axis=0), points.max(axis=0)
    extent = float((high - low).max())
    return QuantizationGrid(origin=tuple(float(x) for x in low), range=extent if extent > 0 else 1.0, bits=bits)


def encode_frame(vertices: np.ndarray, faces: np.ndarray, vertex_ids: np.ndarray, grid: QuantizationGrid,
                 compression_level: int = DEFAULT_COMPRESSION_LEVEL, id_type=np.uint32) -> bytes:
    """Draco mesh bytes (edgebreaker) of #V by 3 positions, #F by 3 triangles and #V vertex ids.

    id_type: np.uint32 (.drc files) or np.float32 (glTF, whose vertex attributes cannot be
    UNSIGNED_INT; exact for ids below 2**24).
    """
    import DracoPy

    ids = np.asarray(vertex_ids).astype(id_type).reshape(-1, 1)
    return DracoPy.encode(np.asarray(vertices, dtype=np.float64), np.asarray(faces, dtype=np.uint32),
                          quantization_bits=grid.bits, compression_level=compression_level,
                          quantization_range=grid.range, quantization_origin=list(grid.origin),
                          create_metadata=True, generic_attributes={ID_ATTRIBUTE: ids})


@dataclass(frozen=True)
class DecodedMesh:
    """A decoded Draco mesh.

    vertices: #D by 3 positions; faces: #F by 3; vertex_ids: #D original ids (None without them);
    method: the header's encoding method (EDGEBREAKER or 0 for sequential);
    attribute_ids: Draco unique id of "POSITION" and of ID_ATTRIBUTE (when present).
    """
    vertices: np.ndarray
    faces: np.ndarray
    vertex_ids: Optional[np.ndarray]
    method: int
    attribute_ids: Dict[str, int]


def decode(data: bytes) -> DecodedMesh:
    """Decode Draco mesh bytes (with the "original_id" attribute when present)."""
    import DracoPy

    mesh = DracoPy.decode(data)
    ids, attribute_ids = None, {}
    for attribute in mesh.attributes:
        if attribute["attribute_type"] == DracoPy.AttributeType.POSITION:
            attribute_ids["POSITION"] = attribute["unique_id"]
        elif attribute["name"] == ID_ATTRIBUTE:
            attribute_ids[ID_ATTRIBUTE] = attribute["unique_id"]
            ids = np.asarray(attribute["data"]).reshape(-1).astype(np.int64)
    return DecodedMesh(vertices=np.asarray(mesh.points, dtype=np.float64), faces=np.asarray(mesh.faces, dtype=np.int64),
                       vertex_ids=ids, method=data[_HEADER_METHOD_BYTE], attribute_ids=attribute_ids)
