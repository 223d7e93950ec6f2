"""Consistent simplification of an example set: one triangle list for the rest pose and every example.

Two simplifiers, one contract (meshik/decimate.h): half-edge collapses onto existing vertices, so
the simplified mesh keeps a subset of the original vertices and every pose lies exactly on its own
vertices; the handle vertices are locked; the error of a collapse is the quadric error summed over
the rest pose and every example; a collapse is refused when it would flip or degenerate a triangle
in any pose, or leave a removed vertex farther than a bound from the simplified surface in any pose
(or a simplified triangle's sample points from the original surface). The bound is
DISTANCE_BOUND_FACTOR times the worst such distance of the rest pose decimated alone to the same
size, relaxed by RELAX_FACTOR (decimation going on) while the target is not reached.
- "fast": MeshIK's own decimator in C++ (meshik._core.decimate_fast): a heap of collapses whose
  guards are checked when popped; on all cores, the same result for any thread count.
- "openmesh": OpenMesh's decimater in C++ (meshik._core.decimate), which re-checks every guard of
  every collapse whose neighbourhood changed: several times slower.

Both return a SimplifiedMeshes: the simplified example set and the vertex correspondence.
simplify_animation simplifies an animation posed at full resolution together with its example set:
its frames count as further poses, so every simplified frame is its full frame restricted to the
kept vertices.
"""
import functools
from dataclasses import dataclass, replace
from typing import Optional, Tuple

import numpy as np

from meshik.errors import PipelineError
from meshik.inputs.meshio import ExampleMeshes

SIMPLIFIERS = ("fast", "openmesh")
# The distance bound: this times the rest pose's own worst distance (rest decimated alone to the
# same size); multiplied by RELAX_FACTOR, at most MAX_RELAXATIONS times, while the target triangle
# count is not reached (then lifted).
DISTANCE_BOUND_FACTOR = 1.3
RELAX_FACTOR = 1.25
MAX_RELAXATIONS = 20


@dataclass(frozen=True)
class SimplifiedMeshes:
    """A simplified example set and how its vertices correspond to the full-resolution ones.

    meshes:          the simplified rest, triangles and examples (#S vertices)
    vertex_map:      #V: the simplified vertex that each original vertex was merged into
    source_vertex:   #S: the original vertex each simplified vertex is (in every pose)
    distance_bound:  the bound on a removed vertex's distance from the simplified surface in any
                     pose at the end (inf: none was kept)
    relaxations:     how many times that bound was relaxed to reach the target
    """
    meshes: ExampleMeshes
    vertex_map: np.ndarray
    source_vertex: np.ndarray
    distance_bound: float
    relaxations: int


def simplify(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray, method: str = "fast",
             threads: Optional[int] = None) -> SimplifiedMeshes:
    """Simplify an example set to about `target_triangles` triangles with the named method.

    handles: #H original vertex indices, locked (each stays a vertex of its own, in place).
    threads: the fast simplifier's (None: all cores; the same result for any count); unused by "openmesh".
    Raises PipelineError for an unknown method, a target not below the current triangle count, or a
    mesh the decimator refuses (naming the rest file): a triangle with a vertex out of range or twice,
    and for "openmesh" a non-manifold or inconsistently oriented mesh ("fast" keeps those vertices).
    """
    if method not in SIMPLIFIERS:
        raise PipelineError(f"unknown simplifier {method!r} (choose from: {', '.join(SIMPLIFIERS)})")
    if not 4 <= target_triangles < len(meshes.faces):
        raise PipelineError(f"cannot simplify {len(meshes.faces)} triangles to {target_triangles}: "
                            f"the target must be at least 4 and below the current count")
    from meshik import _core

    if method == "fast":
        decimate = functools.partial(_core.decimate_fast, threads=0 if threads is None else threads)
    elif hasattr(_core, "decimate"):
        decimate = _core.decimate
    else:
        raise PipelineError("this build of meshik._core has no OpenMesh decimator (bind_decimate not registered): "
                            "use --simplifier fast")
    return _decimate(meshes, target_triangles, np.asarray(handles, dtype=np.int64), decimate)


def simplify_animation(meshes: ExampleMeshes, frames: np.ndarray, target_triangles: int, handles: np.ndarray,
                       method: str = "fast", threads: Optional[int] = None) -> Tuple[SimplifiedMeshes, np.ndarray]:
    """Simplify an example set and an animation posed from it at full resolution, alike.

    frames: #frames by #V by 3 posed positions. The frames join the examples as further poses (in the
    quadric and in the guards), so each simplified frame is its full frame restricted to the kept
    vertices. threads: as simplify's. Returns (the simplified example set, #frames by #S by 3
    simplified frames). Raises PipelineError as simplify does.
    """
    count = len(meshes.examples)
    together = replace(meshes, examples=tuple(meshes.examples) + tuple(np.asarray(frames, dtype=np.float64)))
    simplified = simplify(together, target_triangles, handles, method, threads)
    poses = simplified.meshes.examples
    examples = replace(simplified.meshes, examples=poses[:count])
    return replace(simplified, meshes=examples), np.stack(poses[count:])


def _decimate(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray, decimate) -> SimplifiedMeshes:
    """Decimation driven by every pose, handles locked, distance bounded (see module doc).

    decimate: _core.decimate or _core.decimate_fast (the same arguments and result).
    """
    faces = meshes.faces.astype(np.int32)
    locked = handles.astype(np.int32)
    try:
        *_, rest_error, _, _ = decimate(meshes.rest, faces, [], locked, target_triangles)
        kept, simplified_faces, vertex_map, _, bound, relaxations = decimate(
            meshes.rest, faces, list(meshes.examples), locked, target_triangles,
            max_distance=DISTANCE_BOUND_FACTOR * rest_error if rest_error > 0 else np.inf,
            relax_factor=RELAX_FACTOR, max_relaxations=MAX_RELAXATIONS)
    except ValueError as error:  # meshik.InputError: a bad triangle (openmesh: also a non-manifold one)
        raise PipelineError(f"{meshes.rest_path}: {error}") from None
    kept = np.asarray(kept, dtype=np.int64)
    simplified = replace(meshes, rest=meshes.rest[kept], faces=np.asarray(simplified_faces, dtype=np.int64),
                         examples=tuple(example[kept] for example in meshes.examples))
    return SimplifiedMeshes(meshes=simplified, vertex_map=np.asarray(vertex_map, dtype=np.int64), source_vertex=kept,
                            distance_bound=float(bound), relaxations=relaxations)


def remap_handles(simplified: Optional[SimplifiedMeshes], handles: np.ndarray):
    """(simplified handle indices #K, for each of them its position in `handles` #K).

    Handles merged into one simplified vertex keep the first of them (and its target). Without
    simplification the handles are returned unchanged.
    """
    handles = np.asarray(handles, dtype=np.int64)
    if simplified is None:
        return handles, np.arange(len(handles))
    mapped = simplified.vertex_map[handles]
    _, first = np.unique(mapped, return_index=True)
    first = np.sort(first)
    return mapped[first], first
