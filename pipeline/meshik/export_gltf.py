"""One binary glTF (.glb) per animation: a Draco-compressed base mesh, the frames as morph targets.

This module writes the Draco variant (`--glb draco`); export_gltf_quantized writes the quantized
and meshopt ones with the same node / mesh / animation layout (animation_document).

Layout: one mesh with one primitive whose POSITION, indices and "_ORIGINAL_ID" live in a
KHR_draco_mesh_compression buffer (the rest pose); one morph target per frame (KHR_draco does not
compress morph targets) holding frame - decoded rest, in Draco's decoded vertex order, so that
rest + target k reproduces frame k to float32 precision; one animation that steps the morph
weights through the frames at the file's frame rate (linear in between). The animation's
#frames x #frames weights are one sparse accessor (zero but for each key's own target), so the
file and the writer's memory grow linearly with the frames. Written by hand (gltf_container).
"""
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from meshik.export_draco import ID_ATTRIBUTE, QuantizationGrid, decode, encode_frame
from meshik.gltf_container import (ARRAY_BUFFER, COMPONENT_DTYPES, FLOAT, UNSIGNED_INT, BinaryBuilder, accessor,
                                   glb_bytes, read_accessor, split_glb, view_reader)

DRACO_EXTENSION = "KHR_draco_mesh_compression"
ID_SEMANTIC = "_ORIGINAL_ID"
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


def check_vertex_ids(vertex_ids: np.ndarray) -> None:
    """ValueError unless the #V ids fit the float32 `_ORIGINAL_ID` attribute exactly (below 2**24)."""
    if len(vertex_ids) and int(np.max(vertex_ids)) >= _FLOAT_EXACT_INTEGERS:
        raise ValueError(f"vertex ids up to {_FLOAT_EXACT_INTEGERS} fit a glTF float attribute; got {int(np.max(vertex_ids))}")


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


def rows_of_ids(vertex_ids: np.ndarray, decoded_ids: np.ndarray) -> np.ndarray:
    """For each decoded vertex, the row of `vertex_ids` (distinct ids) that carries its id."""
    order = np.argsort(vertex_ids)
    return order[np.searchsorted(vertex_ids[order], decoded_ids)]


def add_frame_animation(binary: BinaryBuilder, accessors: List[Dict[str, Any]], frame_count: int, fps: float,
                        weights: Optional[np.ndarray] = None) -> int:
    """Append the key times (frame k at k / fps seconds) and the morph weights to `binary` and
    `accessors`: weights (#frames by #targets, dense) when given, else #frames x #frames as one sparse
    accessor (key k sets target k to 1); returns the times' accessor index (the weights' is the next)."""
    times = (np.arange(frame_count) / fps).astype(np.float32)
    times_view = binary.view(times.tobytes())
    accessors.append(accessor(times_view, FLOAT, frame_count, "SCALAR", times.reshape(-1, 1)))
    if weights is not None:
        values = np.asarray(weights, dtype=np.float32).reshape(-1, 1)
        accessors.append(accessor(binary.view(values.tobytes()), FLOAT, len(values), "SCALAR", values))
        return len(accessors) - 2
    keys = np.arange(frame_count, dtype=np.uint32)
    weight_indices_view = binary.view((keys * (frame_count + 1)).tobytes())  # key k sets target k
    weight_values_view = binary.view(np.ones(frame_count, dtype=np.float32).tobytes())
    accessors.append({"componentType": FLOAT, "count": frame_count ** 2, "type": "SCALAR",
                      "sparse": {"count": frame_count,
                                 "indices": {"bufferView": weight_indices_view, "componentType": UNSIGNED_INT},
                                 "values": {"bufferView": weight_values_view}}})
    return len(accessors) - 2


def animation_document(name: str, generator: str, extensions: Sequence[str], node: Dict[str, Any],
                       primitive: Dict[str, Any], frame_names: Sequence[str], times_accessor: int,
                       accessors: List[Dict[str, Any]], binary: BinaryBuilder,
                       first_weights: Optional[Sequence[float]] = None) -> Dict[str, Any]:
    """The glTF JSON of one animated mesh: node (without "mesh" and "name") places mesh 0, whose one
    primitive has the morph targets (extras.targetNames: the frame names when there is one target
    per frame; for a basis "basis j", and extras.frameNames the frames); animation 0 plays the
    weights of `times_accessor`. The mesh's default weights show the first frame (a reader that
    ignores the animation shows it): first_weights (#targets, a basis' first key), or target 0 alone
    when None (one target per frame)."""
    target_count = len(primitive["targets"])
    extras: Dict[str, Any] = {"targetNames": list(frame_names)}
    if target_count != len(frame_names):
        extras = {"targetNames": [f"basis {j}" for j in range(target_count)], "frameNames": list(frame_names)}
    if first_weights is None:
        first_weights = [1.0] + [0.0] * (target_count - 1)
    return {
        "asset": {"version": "2.0", "generator": generator},
        "extensionsUsed": list(extensions),
        "extensionsRequired": list(extensions),
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [dict({"mesh": 0, "name": name}, **node)],
        "meshes": [{"name": name, "primitives": [primitive], "weights": [float(w) for w in first_weights],
                    "extras": extras}],
        "animations": [{"name": name, "samplers": [{"input": times_accessor, "output": times_accessor + 1,
                                                    "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}],
        "accessors": accessors,
        "bufferViews": binary.views,
        "buffers": binary.buffers(),
    }


@dataclass(frozen=True)
class AnimationGlb:
    """What read_animation_glb finds in a MeshIK .glb.

    rest: #D by 3 decoded base positions (Draco order; the rest, or a morph basis' corner);
    faces: #F by 3; vertex_ids: #D; frames: #frames by #D by 3 (rest + the weighted morph targets);
    frame_names; times: #frames seconds; weights: #frames by #targets, the animation's morph weights
    at each key; default_weights: #targets, the mesh's weights without the animation.
    """
    rest: np.ndarray
    faces: np.ndarray
    vertex_ids: np.ndarray
    frames: np.ndarray
    frame_names: Tuple[str, ...]
    times: np.ndarray
    weights: np.ndarray
    default_weights: np.ndarray


def read_animation_glb(data: bytes) -> AnimationGlb:
    """Parse a .glb written by animation_glb or quantized_animation_glb (first mesh, first primitive).
    Raises ValueError."""
    document, binary = split_glb(data)
    primitive = document["meshes"][0]["primitives"][0]
    if DRACO_EXTENSION not in primitive.get("extensions", {}):
        from meshik.export_gltf_quantized import read_quantized_glb

        return read_quantized_glb(document, binary)
    view_bytes = view_reader(document, binary)
    decoded = decode(view_bytes(primitive["extensions"][DRACO_EXTENSION]["bufferView"]))
    base = decoded.vertices.astype(np.float32)
    frames = np.stack([base + read_accessor(document, view_bytes, target["POSITION"]) for target in primitive["targets"]])
    return AnimationGlb(rest=decoded.vertices, faces=decoded.faces, vertex_ids=decoded.vertex_ids,
                        frames=frames.astype(np.float64), frame_names=frame_names_of(document),
                        times=key_times_of(document, view_bytes), weights=key_weights_of(document, view_bytes),
                        default_weights=default_weights_of(document))


def frame_names_of(document: Dict[str, Any]) -> Tuple[str, ...]:
    """The frame names a MeshIK .glb keeps in its mesh's extras (frameNames with a morph basis, else
    targetNames)."""
    extras = document["meshes"][0].get("extras", {})
    return tuple(extras.get("frameNames", extras.get("targetNames", [])))


def default_weights_of(document: Dict[str, Any]) -> np.ndarray:
    """#targets weights of the first mesh without animation (glTF's default: all zero)."""
    mesh = document["meshes"][0]
    return np.asarray(mesh.get("weights", [0.0] * len(mesh["primitives"][0].get("targets", []))), dtype=np.float64)


def key_times_of(document: Dict[str, Any], view_bytes) -> np.ndarray:
    """#frames seconds: the input of animation 0's first sampler."""
    sampler = document["animations"][0]["samplers"][0]
    return read_accessor(document, view_bytes, sampler["input"]).reshape(-1)


def key_weights_of(document: Dict[str, Any], view_bytes) -> np.ndarray:
    """#keys by #targets morph weights: the output of animation 0's first sampler (dense or sparse)."""
    sampler = document["animations"][0]["samplers"][0]
    entry = document["accessors"][sampler["output"]]
    keys = document["accessors"][sampler["input"]]["count"]
    if "sparse" not in entry:
        return read_accessor(document, view_bytes, sampler["output"]).reshape(keys, -1)
    values = np.zeros(entry["count"], dtype=np.float32)
    sparse = entry["sparse"]
    index_type = COMPONENT_DTYPES[sparse["indices"]["componentType"]]
    indices = np.frombuffer(view_bytes(sparse["indices"]["bufferView"]), dtype=index_type, count=sparse["count"],
                            offset=sparse["indices"].get("byteOffset", 0))
    values[indices] = np.frombuffer(view_bytes(sparse["values"]["bufferView"]), dtype="<f4", count=sparse["count"],
                                    offset=sparse["values"].get("byteOffset", 0))
    return values.reshape(keys, -1)
