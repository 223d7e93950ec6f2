"""The layout every MeshIK animation .glb shares, whichever variant wrote it (glb_draco, glb_quantized):
one node, one mesh with one primitive whose morph targets are the frames (or a basis of them), the
`_ORIGINAL_ID` vertex attribute, and one animation that steps the morph weights through the keys;
and the parts of that layout a reader takes back out (frame names, key times, key weights).
"""
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from meshik.export.glb_container import COMPONENT_DTYPES, FLOAT, UNSIGNED_INT, BinaryBuilder, accessor, read_accessor

ID_SEMANTIC = "_ORIGINAL_ID"
_FLOAT_EXACT_INTEGERS = 2 ** 24
_GLB_MAX_BYTES = 2 ** 32 - 1          # the GLB header's 32-bit length
# One animated .glb holds at most this many frames: with one morph target per frame (past the
# morph basis' MAX_BASIS_FRAMES) its weights are #frames squared values, which every reader (and our
# read-back check) expands; 4,096 frames keep that at 64 MB and the write near linear (issue 23).
MAX_GLB_FRAMES = 4096


def glb_size_problem(frames: int, vertices: int) -> Optional[str]:
    """Why an animation of `frames` frames of `vertices` vertices cannot be one .glb, or None.

    Known before posing: the morph targets alone take frames x vertices x 12 bytes.
    """
    if frames > MAX_GLB_FRAMES:
        return f"{frames} frames is more than the {MAX_GLB_FRAMES} one animated .glb holds"
    estimate = frames * (vertices * 12 + 12) + vertices * 16
    if estimate > _GLB_MAX_BYTES:
        return (f"{frames} frames of {vertices} vertices need about {estimate / 2 ** 30:.1f} GiB of morph targets, "
                "more than the 4 GiB a .glb file can hold")
    return None


def check_vertex_ids(vertex_ids: np.ndarray) -> None:
    """ValueError unless the #V ids fit the float32 `_ORIGINAL_ID` attribute exactly (below 2**24)."""
    if len(vertex_ids) and int(np.max(vertex_ids)) >= _FLOAT_EXACT_INTEGERS:
        raise ValueError(f"vertex ids up to {_FLOAT_EXACT_INTEGERS} fit a glTF float attribute; got {int(np.max(vertex_ids))}")


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
