"""What `meshik info` says about a file: a mesh (any format pymeshlab reads), a .drc, a MeshIK
.glb, or a constraint file (validated). Each summary is a flat dict of JSON-friendly values."""
import json
from pathlib import Path
from typing import Any, Dict, List, Tuple

import numpy as np

from meshik.errors import MeshFileError, PipelineError
from meshik.inputs.isolated_load import check_input_file


def describe_files(paths: List) -> Tuple[List[Dict[str, Any]], List[str]]:
    """(one summary per readable file, one error message per unreadable one).

    Meshes after the first also say whether they share the first mesh's triangle list.
    """
    summaries, errors, first = [], [], None
    for path in map(Path, paths):
        try:
            summary, faces = _describe(path)
        except PipelineError as error:
            errors.append(str(error))
            continue
        if faces is not None:
            if first is None:
                first = (path, faces)
            else:
                summary["same_triangles_as"] = {str(first[0]): bool(np.array_equal(faces, first[1]))}
        summaries.append(summary)
    return summaries, errors


def _describe(path: Path):
    """(summary, triangles or None) of one file, by extension."""
    suffix = path.suffix.lower()
    check_input_file(path, "file")
    if suffix == ".drc":
        return _describe_draco(path), None
    if suffix == ".glb":
        return _describe_glb(path), None
    if suffix == ".json":
        return _describe_constraints(path), None
    from meshik.inputs.meshio import load_mesh

    vertices, faces = load_mesh(path)
    summary = {"file": str(path), "kind": "mesh", "vertices": len(vertices), "triangles": len(faces)}
    summary.update(_bounds(vertices))
    summary.update(_edge_counts(faces))
    return summary, faces


def _describe_draco(path: Path) -> Dict[str, Any]:
    """Vertex / triangle counts, encoding method, and whether the original ids are present."""
    from meshik.export.draco import EDGEBREAKER, decode

    try:
        mesh = decode(path.read_bytes())
    except Exception as error:  # noqa: BLE001 - DracoPy raises its own types for corrupt data
        raise MeshFileError(f"{path}: cannot decode Draco data: {error}") from None
    summary = {"file": str(path), "kind": "draco", "vertices": len(mesh.vertices), "triangles": len(mesh.faces),
               "encoding": "edgebreaker" if mesh.method == EDGEBREAKER else "sequential",
               "original_ids": mesh.vertex_ids is not None}
    summary.update(_bounds(mesh.vertices))
    return summary


def _describe_glb(path: Path) -> Dict[str, Any]:
    """Counts of a MeshIK animation .glb: vertices, triangles, frames, duration, and its variant with
    the readers that open it (glb_readers)."""
    from meshik.export.glb_container import split_glb
    from meshik.export.glb_reader import read_animation_glb
    from meshik.export.glb_readers import readers_of, variant_of

    try:
        data = path.read_bytes()
        animation = read_animation_glb(data)
        variant = variant_of(split_glb(data)[0].get("extensionsRequired", []))
    except (ValueError, KeyError, IndexError, TypeError) as error:  # the fields are checked first (gltf_checks)
        detail = " ".join(str(error).split())[:300]
        raise MeshFileError(f"{path}: not a MeshIK animation .glb ({type(error).__name__}: {detail})") from None
    return {"file": str(path), "kind": "glb animation", "vertices": len(animation.rest), "triangles": len(animation.faces),
            "frames": len(animation.frames), "duration_seconds": float(animation.times[-1]) if len(animation.times) else 0.0,
            "morph_targets": int(animation.weights.shape[1]), "variant": variant, **readers_of(variant)}


def _describe_constraints(path: Path) -> Dict[str, Any]:
    """A validated constraint file's contents in numbers (raises ConstraintError when invalid)."""
    from meshik.inputs.constraints import load

    constraints = load(path)
    return {"file": str(path), "kind": "constraints", "rest": str(constraints.rest), "examples": len(constraints.examples),
            "handle_groups": list(constraints.handles), "frames": len(constraints.frames), "fps": constraints.fps,
            "options": json.loads(json.dumps(constraints.solver_options()))}


def _bounds(vertices: np.ndarray) -> Dict[str, Any]:
    """Bounding box corners of #V by 3 positions."""
    if len(vertices) == 0:
        return {}
    return {"bounds_min": vertices.min(axis=0).tolist(), "bounds_max": vertices.max(axis=0).tolist()}


def _edge_counts(faces: np.ndarray) -> Dict[str, int]:
    """Boundary edges (in one triangle) and non-manifold edges (in more than two) of #F by 3 triangles."""
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return {"boundary_edges": int((counts == 1).sum()), "non_manifold_edges": int((counts > 2).sum())}
