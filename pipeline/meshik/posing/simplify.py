"""Consistent simplification of an example set: one triangle list for the rest pose and every example.

Two simplifiers:
- "fast": fast-simplification's quadric decimation of the rest pose, the same edge collapses
  replayed on every example. Replay re-places each merged vertex per pose; a vertex that lands
  far from its pose's surface (or a handle vertex) is put back on a surviving original vertex,
  in every pose alike.
- "openmesh": OpenMesh's decimater in C++ (meshik._core.decimate) with the handle vertices
  locked and the error quadric summed over the rest pose and every example. It keeps a subset
  of the original vertices, so every pose lies exactly on its own vertices. A collapse is also
  refused when a removed vertex would end farther than a bound from the simplified surface in any
  pose, or a simplified triangle's sample points from the original surface; the bound is
  DISTANCE_BOUND_FACTOR times the worst such distance of the rest pose decimated alone to the
  same size, relaxed by RELAX_FACTOR (decimation going on) while the target is not reached.

Both return a SimplifiedMeshes: the simplified example set and the vertex correspondence.
simplify_animation simplifies an animation posed at full resolution together with its example set:
its frames count as further poses (in the OpenMesh quadric and in the fast simplifier's guard), so
every simplified frame is its full frame simplified like the examples.
"""
from dataclasses import dataclass, replace
from typing import Optional, Tuple

import numpy as np

from meshik.errors import PipelineError
from meshik.inputs.meshio import ExampleMeshes
from meshik.posing.surface_distance import point_triangle_distance

SIMPLIFIERS = ("fast", "openmesh")
# A replayed vertex farther than this fraction of the simplified rest mesh's mean edge length from
# the triangles it stands for (in any pose) is moved back onto an original vertex.
DEFAULT_SURFACE_TOLERANCE = 0.5
# fast-simplification's `agg` (its own default): how fast its error threshold grows from pass to
# pass. Lower is closer to collapsing the cheapest edge first but may stop short of the target.
DEFAULT_AGGRESSIVENESS = 7.0
# The openmesh simplifier's distance bound: this times the rest pose's own worst vertex distance
# (rest decimated alone to the same size); multiplied by RELAX_FACTOR, at most MAX_RELAXATIONS
# times, while the target triangle count is not reached (then lifted).
DISTANCE_BOUND_FACTOR = 1.3
RELAX_FACTOR = 1.25
MAX_RELAXATIONS = 20


@dataclass(frozen=True)
class SimplifiedMeshes:
    """A simplified example set and how its vertices correspond to the full-resolution ones.

    meshes:          the simplified rest, triangles and examples (#S vertices)
    vertex_map:      #V: the simplified vertex that each original vertex was merged into
    source_vertex:   #S: the original vertex each simplified vertex stands for (it lies on it in
                     every pose unless the fast simplifier kept its replayed position)
    snapped:         how many vertices the fast simplifier put back on an original vertex
    distance_bound:  the openmesh simplifier's bound on a removed vertex's distance from the
                     simplified surface in any pose (inf: none was kept); None for fast
    relaxations:     how many times the openmesh simplifier relaxed that bound to reach the target
    """
    meshes: ExampleMeshes
    vertex_map: np.ndarray
    source_vertex: np.ndarray
    snapped: int = 0
    distance_bound: Optional[float] = None
    relaxations: int = 0


def simplify(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray, method: str = "fast",
             surface_tolerance: float = DEFAULT_SURFACE_TOLERANCE,
             aggressiveness: float = DEFAULT_AGGRESSIVENESS) -> SimplifiedMeshes:
    """Simplify an example set to about `target_triangles` triangles with the named method.

    handles: #H original vertex indices that must stay vertices of their own (locked by
             "openmesh"; with "fast" they are kept exactly in position but two may merge).
    surface_tolerance, aggressiveness: the fast simplifier's (see simplify_fast); unused by "openmesh".
    Raises PipelineError for an unknown method or a target not below the current triangle count.
    """
    if method not in SIMPLIFIERS:
        raise PipelineError(f"unknown simplifier {method!r} (choose from: {', '.join(SIMPLIFIERS)})")
    if not 4 <= target_triangles < len(meshes.faces):
        raise PipelineError(f"cannot simplify {len(meshes.faces)} triangles to {target_triangles}: "
                            f"the target must be at least 4 and below the current count")
    handles = np.asarray(handles, dtype=np.int64)
    if method == "fast":
        return simplify_fast(meshes, target_triangles, handles, surface_tolerance, aggressiveness)
    return simplify_openmesh(meshes, target_triangles, handles)


def simplify_fast(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray,
                  surface_tolerance: float = DEFAULT_SURFACE_TOLERANCE,
                  aggressiveness: float = DEFAULT_AGGRESSIVENESS) -> SimplifiedMeshes:
    """fast-simplification on the rest pose, its collapses replayed on every example (see module doc).

    surface_tolerance: DEFAULT_SURFACE_TOLERANCE's fraction; aggressiveness: fast-simplification's agg.
    """
    import fast_simplification

    faces = meshes.faces
    poses = (meshes.rest,) + meshes.examples
    _, _, collapses = fast_simplification.simplify(meshes.rest, faces, target_count=target_triangles, agg=aggressiveness,
                                                   return_collapses=True)
    replayed = []
    for pose in poses:
        points, simplified_faces, vertex_map = fast_simplification.replay_simplification(pose, faces, collapses)
        replayed.append(points)
    source_vertex = _representatives(vertex_map, len(points), collapses[:, 1], handles)
    snap = np.zeros(len(points), dtype=bool)
    snap[vertex_map[handles]] = True
    tolerance = surface_tolerance * _mean_edge_length(replayed[0], simplified_faces)
    patches = _patch_pairs(faces, vertex_map)
    for pose, points in zip(poses, replayed):
        snap |= ~(_distance_to_own_patch(points, pose, faces, vertex_map, patches) <= tolerance)  # NaN too
    positions = [np.where(snap[:, None], pose[source_vertex], points) for pose, points in zip(poses, replayed)]
    simplified = replace(meshes, rest=positions[0], faces=np.asarray(simplified_faces, dtype=np.int64),
                         examples=tuple(positions[1:]))
    return SimplifiedMeshes(meshes=simplified, vertex_map=np.asarray(vertex_map, dtype=np.int64),
                            source_vertex=source_vertex, snapped=int(snap.sum()))


def simplify_animation(meshes: ExampleMeshes, frames: np.ndarray, target_triangles: int, handles: np.ndarray,
                       method: str = "fast",
                       aggressiveness: float = DEFAULT_AGGRESSIVENESS) -> Tuple[SimplifiedMeshes, np.ndarray]:
    """Simplify an example set and an animation posed from it at full resolution, alike.

    frames: #frames by #V by 3 posed positions. The frames join the examples as further poses (the
    OpenMesh quadric sums over them; the fast simplifier's collapses, chosen on the rest pose, are
    replayed on them with the same guard), so each simplified frame is the simplification of its
    full frame. aggressiveness: the fast simplifier's (see simplify_fast). Returns (the simplified
    example set, #frames by #S by 3 simplified frames).
    Raises PipelineError as simplify does.
    """
    count = len(meshes.examples)
    together = replace(meshes, examples=tuple(meshes.examples) + tuple(np.asarray(frames, dtype=np.float64)))
    simplified = simplify(together, target_triangles, handles, method, aggressiveness=aggressiveness)
    poses = simplified.meshes.examples
    examples = replace(simplified.meshes, examples=poses[:count])
    return replace(simplified, meshes=examples), np.stack(poses[count:])


def _representatives(vertex_map: np.ndarray, count: int, removed: np.ndarray, handles: np.ndarray) -> np.ndarray:
    """#S original vertex standing for each simplified vertex: its first handle, else its lowest survivor.

    vertex_map: #V original -> simplified; removed: original vertices collapsed away.
    """
    representative = np.full(count, -1, dtype=np.int64)
    survivors = np.setdiff1d(np.arange(len(vertex_map)), removed)
    # each pass overrides the previous one: any member < lowest survivor < first handle
    for candidates in (np.arange(len(vertex_map)), survivors, handles):
        clusters, first = np.unique(vertex_map[candidates], return_index=True)
        representative[clusters] = candidates[first]
    return representative


def _patch_pairs(faces: np.ndarray, vertex_map: np.ndarray) -> np.ndarray:
    """#pairs by 2 (simplified vertex, original triangle touching one of its merged vertices), unique.

    faces: #F by 3 original triangles; vertex_map: #V original -> simplified.
    """
    return np.unique(np.stack([vertex_map[faces].ravel(), np.repeat(np.arange(len(faces)), 3)], axis=1), axis=0)


def _distance_to_own_patch(points: np.ndarray, pose: np.ndarray, faces: np.ndarray, vertex_map: np.ndarray,
                           pairs: Optional[np.ndarray] = None) -> np.ndarray:
    """#S distances from each simplified vertex to the original triangles touching its merged vertices.

    points: #S by 3 simplified positions; pose: #V by 3 original positions; faces: #F by 3 original;
    pairs: _patch_pairs(faces, vertex_map) when already known.
    """
    pairs = _patch_pairs(faces, vertex_map) if pairs is None else pairs
    corners = pose[faces[pairs[:, 1]]]
    distance = point_triangle_distance(points[pairs[:, 0]], corners[:, 0], corners[:, 1], corners[:, 2])
    nearest = np.full(len(points), np.inf)
    np.minimum.at(nearest, pairs[:, 0], distance)
    return nearest


def _mean_edge_length(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Mean length of the triangle edges (each counted once per triangle side)."""
    corners = vertices[faces]
    return float(np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2).mean())


def simplify_openmesh(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray) -> SimplifiedMeshes:
    """OpenMesh decimation driven by every pose, handles locked, distance bounded (see module doc)."""
    from meshik import _core

    if not hasattr(_core, "decimate"):
        raise PipelineError("this build of meshik._core has no OpenMesh decimator (bind_decimate not registered): "
                            "use --simplifier fast")
    faces = meshes.faces.astype(np.int32)
    locked = handles.astype(np.int32)
    try:
        *_, rest_error, _, _ = _core.decimate(meshes.rest, faces, [], locked, target_triangles)
        kept, simplified_faces, vertex_map, _, bound, relaxations = _core.decimate(
            meshes.rest, faces, list(meshes.examples), locked, target_triangles,
            max_distance=DISTANCE_BOUND_FACTOR * rest_error if rest_error > 0 else np.inf,
            relax_factor=RELAX_FACTOR, max_relaxations=MAX_RELAXATIONS)
    except ValueError as error:  # meshik.InputError: a non-manifold or inconsistently oriented mesh
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
