"""The quantized animation .glb (`--glb quantized`) and its meshopt-compressed form (`--glb meshopt`).

Positions and morph-target deltas are integers on one grid shared by every frame
(KHR_mesh_quantization): the base POSITION is UNSIGNED_SHORT grid coordinates q_rest, target k is
SHORT q_k - q_rest (the deltas share the base's dequantization, as the extension requires), and the
node's translation (the grid's origin) and uniform scale (its step) turn grid units into the
solver's coordinates. targets="frames": one target per frame, rest + target k decodes to the grid
point nearest frame k, the weights are one sparse accessor; targets="basis" (morph_basis): r < #frames
SHORT targets on an UNSIGNED_SHORT base at the corner of the weights' box, in a node unit finer than
the grid (the node's scale), and dense #frames x r weights inside [0, 1] whose decoding stays within
BASIS_TOLERANCE grid units of every frame (the per-frame files' own bound), one target per frame
when no smaller basis does. Every variant's weights lie in [0, 1] (readers that map morph targets
to shape-key sliders, as Blender's importer does, clamp them there), and the mesh's default weights
are the first key's.
Elements are padded to 8 bytes (4 shorts). `_ORIGINAL_ID` (float32, exact below 2**24) keeps each vertex's
input id. No normals: the deltas of normals would add a stream per frame; viewers compute them.
Triangles are in meshoptimizer's vertex-cache order; vertices in a nearest-neighbour walk over the
surface (_meshopt.surface_walk), so that consecutive vertices, whose difference the vertex codec
stores, move alike: the morph targets code in about 19% fewer bytes than in first-use order;
with meshopt every buffer view (vertex, index, targets, animation) is EXT_meshopt_compression
encoded by the meshoptimizer library (meshik._meshopt, vertex codec version 0).
"""
from typing import Any, Dict, List, Sequence, Tuple

import numpy as np

from meshik.export.draco import QuantizationGrid
from meshik.export.glb_container import (ARRAY_BUFFER, FLOAT, MESHOPT_EXTENSION, SHORT, UNSIGNED_SHORT,
                                         BinaryBuilder, MeshoptBinaryBuilder, accessor, glb_bytes, read_accessor,
                                         view_reader)
from meshik.export.glb_layout import (ID_SEMANTIC, AnimationGlb, add_frame_animation, animation_document,
                                      check_vertex_ids, default_weights_of, frame_names_of, glb_size_problem,
                                      key_times_of, key_weights_of)
from meshik.export.morph_basis import low_rank_basis, morphed_positions

QUANTIZATION_EXTENSION = "KHR_mesh_quantization"
MAX_POSITION_BITS = 15   # deltas between grid points must fit a SHORT
GLB_TARGETS = ("basis", "frames")
# half a grid cell's diagonal (the rounding of the per-frame file), less a margin for viewers that sum
# the targets in another float32 order
BASIS_TOLERANCE = np.sqrt(3) / 2 - 1 / 16


def quantized_animation_glb(rest: np.ndarray, faces: np.ndarray, frames: np.ndarray, frame_names: Sequence[str],
                            vertex_ids: np.ndarray, grid: QuantizationGrid, fps: float, name: str, generator: str,
                            meshopt: bool = True, targets: str = "basis") -> bytes:
    """GLB bytes of an animation, quantized on `grid` (which must cover rest and every frame) and,
    when meshopt, compressed with EXT_meshopt_compression.

    rest: #V by 3; faces: #F by 3; frames: #frames by #V by 3; vertex_ids: #V ids stored per vertex;
    fps: frames per second; targets: "basis" or "frames" (see the module). Raises ValueError for a
    grid finer than MAX_POSITION_BITS, ids past 2**24, non-finite positions, unknown targets or an
    animation too large for one .glb.
    """
    from meshik import _meshopt

    if not 1 <= grid.bits <= MAX_POSITION_BITS:
        raise ValueError(f"position bits must be between 1 and {MAX_POSITION_BITS} for a quantized .glb, got {grid.bits}")
    if targets not in GLB_TARGETS:
        raise ValueError(f"glb targets must be one of {', '.join(GLB_TARGETS)}, got {targets!r}")
    check_vertex_ids(vertex_ids)
    frames = np.asarray(frames, dtype=np.float64)
    problem = glb_size_problem(len(frames), len(rest))
    if problem:
        raise ValueError(problem)
    if not (np.isfinite(rest).all() and np.isfinite(frames).all()):
        raise ValueError("positions are not all finite")
    triangles = _meshopt.optimize_vertex_cache(np.asarray(faces, dtype=np.uint32).reshape(-1), len(rest))
    old_of_new = _meshopt.surface_walk(triangles, np.ascontiguousarray(rest, dtype=np.float64)).astype(np.int64)
    new_of_old = np.argsort(old_of_new)
    base = _grid_coordinates(np.asarray(rest, dtype=np.float64)[old_of_new], grid)
    basis = low_rank_basis(base, (frames[:, old_of_new] - np.asarray(grid.origin)) / grid.step, BASIS_TOLERANCE) \
        if targets == "basis" else None
    origin = np.asarray(grid.origin, dtype=np.float64)
    node = {"translation": origin.tolist(), "scale": [grid.step] * 3}
    if basis is None:
        deltas = _grid_coordinates(frames[:, old_of_new], grid) - base
    else:  # the basis' corner, stored from its smallest coordinates, in its own node unit
        offset = basis.base.min(axis=0)
        base, deltas, unit = basis.base - offset, basis.targets, grid.step * basis.unit
        node = {"translation": (origin + offset * unit).tolist(), "scale": [unit] * 3}

    binary = MeshoptBinaryBuilder() if meshopt else BinaryBuilder()
    count = len(rest)
    position_view = binary.view(_padded(base, np.uint16).tobytes(), stride=8, target=ARRAY_BUFFER)
    ids = np.asarray(vertex_ids)[old_of_new].astype(np.float32).reshape(-1, 1)
    id_view = binary.view(ids.tobytes(), stride=4, target=ARRAY_BUFFER)
    index_view, index_type = binary.index_view(new_of_old[triangles], count)
    targets_view = binary.view(_padded(deltas, np.int16).tobytes(), stride=8, target=ARRAY_BUFFER)
    accessors: List[Dict[str, Any]] = [
        accessor(position_view, UNSIGNED_SHORT, count, "VEC3", base),
        dict(accessor(index_view, index_type, len(triangles), "SCALAR", triangles.reshape(-1, 1)),
             min=[0], max=[count - 1]),
        accessor(id_view, FLOAT, count, "SCALAR", ids),
    ]
    for k, delta in enumerate(deltas):
        accessors.append(accessor(targets_view, SHORT, count, "VEC3", delta, byte_offset=k * count * 8))
    times_accessor = add_frame_animation(binary, accessors, len(frames), fps, None if basis is None else basis.weights)
    primitive = {"attributes": {"POSITION": 0, ID_SEMANTIC: 2}, "indices": 1, "mode": 4,
                 "targets": [{"POSITION": 3 + k} for k in range(len(deltas))]}
    extensions = [QUANTIZATION_EXTENSION] + ([MESHOPT_EXTENSION] if meshopt else [])
    document = animation_document(name, generator, extensions, node, primitive, frame_names, times_accessor, accessors,
                                  binary, None if basis is None else basis.weights[0])
    return glb_bytes(document, bytes(binary.data))


def _grid_coordinates(points: np.ndarray, grid: QuantizationGrid) -> np.ndarray:
    """Integer grid coordinates (int32, same shape) of points (..., 3) on `grid`, clamped to it."""
    scaled = np.rint((points - np.asarray(grid.origin)) / grid.step)
    return np.clip(scaled, 0, 2 ** grid.bits - 1).astype(np.int32)


def _padded(values: np.ndarray, dtype) -> np.ndarray:
    """(..., 3) values as (..., 4) of dtype with a zero 4th component (glTF's 4-byte element alignment)."""
    out = np.zeros(values.shape[:-1] + (4,), dtype=dtype)
    out[..., :3] = values
    return out


def read_quantized_glb(document: Dict[str, Any], binary: bytes) -> AnimationGlb:
    """The animation of a quantized (optionally meshopt-compressed) MeshIK .glb, dequantized with
    its node's translation and scale. document, binary: as glb_container.split_glb returns them."""
    view_bytes = view_reader(document, binary)
    primitive = document["meshes"][0]["primitives"][0]
    translation, scale = _node_transform(document["nodes"][0])
    base = read_accessor(document, view_bytes, primitive["attributes"]["POSITION"]).astype(np.float64)
    deltas = np.stack([read_accessor(document, view_bytes, target["POSITION"]) for target in primitive["targets"]])
    weights = key_weights_of(document, view_bytes)
    faces = read_accessor(document, view_bytes, primitive["indices"]).reshape(-1, 3).astype(np.int64)
    ids = read_accessor(document, view_bytes, primitive["attributes"][ID_SEMANTIC]).reshape(-1).astype(np.int64)
    return AnimationGlb(rest=translation + scale * base, faces=faces, vertex_ids=ids,
                        frames=translation + scale * morphed_positions(base, weights, deltas).astype(np.float64),
                        frame_names=frame_names_of(document), times=key_times_of(document, view_bytes), weights=weights,
                        default_weights=default_weights_of(document))


def _node_transform(node: Dict[str, Any]) -> Tuple[np.ndarray, np.ndarray]:
    """(translation, scale) 3-vectors of a node with neither rotation nor matrix (ValueError otherwise)."""
    if "matrix" in node or "rotation" in node:
        raise ValueError("the mesh's node is rotated: not a MeshIK quantized .glb")
    return np.asarray(node.get("translation", [0.0] * 3), dtype=np.float64), np.asarray(node.get("scale", [1.0] * 3), dtype=np.float64)
