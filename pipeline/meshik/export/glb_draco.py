"""One binary glTF (.glb) per animation: a Draco-compressed base mesh, the frames as morph targets.

This module writes and reads the Draco variant (`--glb draco`); glb_quantized writes the quantized
and meshopt ones with the same node / mesh / animation layout (glb_layout); glb_reader reads any.

Layout: one mesh with one primitive whose POSITION, indices and "_ORIGINAL_ID" live in a
KHR_draco_mesh_compression buffer (the rest pose); one morph target per frame (KHR_draco does not
compress morph targets) holding frame - decoded rest, in Draco's decoded vertex order, so that
rest + target k reproduces frame k to float32 precision; one animation that steps the morph
weights through the frames at the file's frame rate (linear in between). The animation's
#frames x #frames weights are one sparse accessor (zero but for each key's own target), so the
file and the writer's memory grow linearly with the frames. Written by hand (glb_container).
"""
from typing import Any, Dict, List, Sequence

import numpy as np

from meshik.export.draco import ID_ATTRIBUTE, QuantizationGrid, decode, encode_frame
from meshik.export.glb_container import (ARRAY_BUFFER, FLOAT, UNSIGNED_INT, BinaryBuilder, accessor, glb_bytes,
                                         read_accessor, view_reader)
from meshik.export.glb_layout import (ID_SEMANTIC, AnimationGlb, add_frame_animation, animation_document,
                                      check_vertex_ids, default_weights_of, frame_names_of, glb_size_problem, key_times_of, key_weights_of,
                                      rows_of_ids)

DRACO_EXTENSION = "KHR_draco_mesh_compression"


def animation_glb(rest: np.ndarray, faces: np.ndarray, frames: np.ndarray, frame_names: Sequence[str],
                  vertex_ids: np.ndarray, grid: QuantizationGrid, fps: float, name: str, generator: str) -> bytes:
    """GLB bytes of an animation.

    rest: #V by 3 base positions; faces: #F by 3; frames: #frames by #V by 3 positions;
    vertex_ids: #V ids stored per vertex (e.g. the full-resolution vertex ids); grid: the Draco
    quantisation of the base mesh; fps: frames per second of the animation.
    """
    check_vertex_ids(vertex_ids)
    draco = encode_frame(rest, faces, vertex_ids, grid, id_type=np.float32)
    decoded = decode(draco)
    local = rows_of_ids(np.asarray(vertex_ids), decoded.vertex_ids)
    base = decoded.vertices.astype(np.float32)
    targets = (np.asarray(frames, dtype=np.float64)[:, local] - base.astype(np.float64)).astype(np.float32)
    problem = glb_size_problem(len(frames), len(base))
    if problem:
        raise ValueError(problem)
    binary = BinaryBuilder()
    draco_view = binary.view(draco)
    targets_view = binary.view(targets.tobytes(), stride=12, target=ARRAY_BUFFER)

    count = len(base)
    accessors: List[Dict[str, Any]] = [
        accessor(None, FLOAT, count, "VEC3", base),
        {"componentType": UNSIGNED_INT, "count": int(decoded.faces.size), "type": "SCALAR"},
        accessor(None, FLOAT, count, "SCALAR", decoded.vertex_ids.reshape(-1, 1).astype(np.float32)),
    ]
    for k, target in enumerate(targets):
        accessors.append(accessor(targets_view, FLOAT, count, "VEC3", target, byte_offset=k * count * 12))
    times_accessor = add_frame_animation(binary, accessors, len(frames), fps)

    primitive = {
        "attributes": {"POSITION": 0, ID_SEMANTIC: 2},
        "indices": 1,
        "mode": 4,
        "targets": [{"POSITION": 3 + k} for k in range(len(frames))],
        "extensions": {DRACO_EXTENSION: {"bufferView": draco_view, "attributes": {
            "POSITION": decoded.attribute_ids["POSITION"], ID_SEMANTIC: decoded.attribute_ids[ID_ATTRIBUTE]}}},
    }
    document = animation_document(name, generator, [DRACO_EXTENSION], {}, primitive, frame_names, times_accessor,
                                  accessors, binary)
    return glb_bytes(document, bytes(binary.data))


def read_draco_glb(document: Dict[str, Any], binary: bytes) -> AnimationGlb:
    """The animation in a Draco-variant .glb, from its JSON document and binary chunk (split_glb).
    Raises ValueError."""
    view_bytes = view_reader(document, binary)
    primitive = document["meshes"][0]["primitives"][0]
    decoded = decode(view_bytes(primitive["extensions"][DRACO_EXTENSION]["bufferView"]))
    base = decoded.vertices.astype(np.float32)
    frames = np.stack([base + read_accessor(document, view_bytes, target["POSITION"]) for target in primitive["targets"]])
    return AnimationGlb(rest=decoded.vertices, faces=decoded.faces, vertex_ids=decoded.vertex_ids,
                        frames=frames.astype(np.float64), frame_names=frame_names_of(document),
                        times=key_times_of(document, view_bytes), weights=key_weights_of(document, view_bytes),
                        default_weights=default_weights_of(document))
