"""Consistent simplification of an example set: one triangle list for the rest pose and every example.

Two simplifiers:
- "fast": fast-simplification's quadric decimation of the rest pose, the same edge collapses
  replayed on every example. Replay re-places each merged vertex per pose; a vertex that lands
  far from its pose's surface (or a handle vertex) is put back on a surviving original vertex,
  in every pose alike.
- "openmesh": OpenMesh's decimater in C++ (meshik._core.decimate) with the handle vertices
  locked and the error quadric summed over the rest pose and every example. It keeps a subset
  of the original vertices, so every pose lies exactly on its own vertices.

Both return a SimplifiedMeshes: the simplified example set and the vertex correspondence.
simplify_poses applies the same simplification to any other pose of the full mesh (e.g. every
frame posed at full resolution): the collapses replayed with the same guard ("fast"), or the
kept vertices' positions ("openmesh").
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


@dataclass(frozen=True)
class SimplifiedMeshes:
    """A simplified example set and how its vertices correspond to the full-resolution ones.

    meshes:          the simplified rest, triangles and examples (#S vertices)
    vertex_map:      #V: the simplified vertex that each original vertex was merged into
    source_vertex:   #S: the original vertex each simplified vertex stands for (it lies on it in
                     every pose unless the fast simplifier kept its replayed position)
    snapped:         how many vertices the fast simplifier put back on an original vertex
    collapses:       the fast simplifier's edge collapses (fast-simplification's #C by 2), None for "openmesh"
    snap_mask:       #S: which vertices the fast simplifier put back (None for "openmesh")
    tolerance:       the fast simplifier's distance beyond which a replayed vertex is put back
    """
    meshes: ExampleMeshes
    vertex_map: np.ndarray
    source_vertex: np.ndarray
    snapped: int = 0
    collapses: Optional[np.ndarray] = None
    snap_mask: Optional[np.ndarray] = None
    tolerance: float = 0.0


def simplify(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray, method: str = "fast",
             surface_tolerance: float = DEFAULT_SURFACE_TOLERANCE) -> SimplifiedMeshes:
    """Simplify an example set to about `target_triangles` triangles with the named method.

    handles: #H original vertex indices that must stay vertices of their own (locked by
             "openmesh"; with "fast" they are kept exactly in position but two may merge).
    Raises PipelineError for an unknown method or a target not below the current triangle count.
    """
    if method not in SIMPLIFIERS:
        raise PipelineError(f"unknown simplifier {method!r} (choose from: {', '.join(SIMPLIFIERS)})")
    if not 4 <= target_triangles < len(meshes.faces):
        raise PipelineError(f"cannot simplify {len(meshes.faces)} triangles to {target_triangles}: "
                            f"the target must be at least 4 and below the current count")
    handles = np.asarray(handles, dtype=np.int64)
    if method == "fast":
        return simplify_fast(meshes, target_triangles, handles, surface_tolerance)
    return simplify_openmesh(meshes, target_triangles, handles)


def simplify_fast(meshes: ExampleMeshes, target_triangles: int, handles: np.ndarray,
                  surface_tolerance: float = DEFAULT_SURFACE_TOLERANCE) -> SimplifiedMeshes:
    """fast-simplification on the rest pose, its collapses replayed on every example (see module doc)."""
    import fast_simplification

    faces = meshes.faces
    poses = (meshes.rest,) + meshes.examples
    _, _, collapses = fast_simplification.simplify(meshes.rest, faces, target_count=target_triangles, return_collapses=True)
    points, simplified_faces, vertex_map = fast_simplification.replay_simplification(meshes.rest, faces, collapses)
    vertex_map = np.asarray(vertex_map, dtype=np.int64)
    source_vertex = _representatives(vertex_map, len(points), collapses[:, 1], handles)
    snap = np.zeros(len(points), dtype=bool)
    snap[vertex_map[handles]] = True
    tolerance = surface_tolerance * _mean_edge_length(points, simplified_faces)
    positions, snap = _replay_guarded(np.stack(poses), faces, collapses, vertex_map, source_vertex, snap, tolerance)
    simplified = replace(meshes, rest=positions[0], faces=np.asarray(simplified_faces, dtype=np.int64),
                         examples=tuple(positions[1:]))
    return SimplifiedMeshes(meshes=simplified, vertex_map=vertex_map, source_vertex=source_vertex,
                            snapped=int(snap.sum()), collapses=collapses, snap_mask=snap, tolerance=tolerance)


def simplify_poses(simplified: SimplifiedMeshes, faces: np.ndarray, poses: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """The simplification of other poses of the full mesh, as `simplified` did it to its example set.

    faces: #F by 3 full-resolution triangles; poses: #P by #V by 3 full-resolution positions (e.g.
    the rest pose followed by every posed frame). Returns (#P by #S by 3 positions on the simplified
    triangles, #S mask of the vertices put back on their original vertex). "openmesh": the kept
    vertices' positions, bit for bit. "fast": the collapses replayed on every pose; a vertex put back
    in the example set, or landing farther than the tolerance from its own patch in any of these
    poses, is put back on its original vertex in all of them alike (no vertex switches between
    frames), so handles sit on their own positions.
    """
    poses = np.asarray(poses, dtype=np.float64)
    if simplified.collapses is None:
        return poses[:, simplified.source_vertex], np.zeros(len(simplified.source_vertex), dtype=bool)
    return _replay_guarded(poses, faces, simplified.collapses, simplified.vertex_map, simplified.source_vertex,
                           simplified.snap_mask, simplified.tolerance)


def _replay_guarded(poses: np.ndarray, faces: np.ndarray, collapses: np.ndarray, vertex_map: np.ndarray,
                    source_vertex: np.ndarray, snap: np.ndarray, tolerance: float) -> Tuple[np.ndarray, np.ndarray]:
    """Replay the collapses on every pose and put vertices back on their original vertex.

    poses: #P by #V by 3; vertex_map: #V original -> simplified; source_vertex: #S; snap: #S vertices
    put back whatever their distance; tolerance: put back too any vertex farther than this from the
    original triangles it stands for, in any pose. Returns (#P by #S by 3 positions, #S final mask).
    """
    import fast_simplification

    replayed = np.stack([fast_simplification.replay_simplification(pose, faces, collapses)[0] for pose in poses])
    snap = snap.copy()
    patches = _patch_pairs(faces, vertex_map)
    for pose, points in zip(poses, replayed):
        snap |= ~(_distance_to_own_patch(points, pose, faces, vertex_map, patches) <= tolerance)  # NaN too
    return np.where(snap[None, :, None], poses[:, source_vertex], replayed), snap


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
    """OpenMesh decimation driven by every pose, handles locked (see module doc)."""
    from meshik import _core

    if not hasattr(_core, "decimate"):
        raise PipelineError("this build of meshik._core has no OpenMesh decimator (bind_decimate not registered): "
                            "use --simplifier fast")
    try:
        kept, faces, vertex_map = _core.decimate(meshes.rest, meshes.faces.astype(np.int32), list(meshes.examples),
                                                 handles.astype(np.int32), target_triangles)
    except ValueError as error:  # meshik.InputError: a non-manifold or inconsistently oriented mesh
        raise PipelineError(f"{meshes.rest_path}: {error}") from None
    kept = np.asarray(kept, dtype=np.int64)
    simplified = replace(meshes, rest=meshes.rest[kept], faces=np.asarray(faces, dtype=np.int64),
                         examples=tuple(example[kept] for example in meshes.examples))
    return SimplifiedMeshes(meshes=simplified, vertex_map=np.asarray(vertex_map, dtype=np.int64), source_vertex=kept)


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
