"""Small generated example sets for the pipeline tests: a tube and its bent poses, as OBJ files.

The tube stands along z from 0 to `length`; its bottom ring is vertices 0..segments-1 and its top
ring the last `segments` vertices. Bent poses curve the centre line into a circular arc.
"""
import json
import pathlib
from typing import Dict, List, Sequence

import numpy as np


def tube(rings: int = 12, segments: int = 10, length: float = 4.0, radius: float = 0.5):
    """(rings*segments by 3 vertices, triangles) of an open tube along z (rings of `segments` vertices)."""
    angles = np.arange(segments) * 2 * np.pi / segments
    heights = np.linspace(0.0, length, rings)
    vertices = np.array([[radius * np.cos(a), radius * np.sin(a), z] for z in heights for a in angles])
    faces = []
    for r in range(rings - 1):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            faces += [[a, b, b + segments], [a, b + segments, a + segments]]
    return vertices, np.array(faces)


def bend(vertices: np.ndarray, degrees: float, axis: str = "y", length: float = 4.0) -> np.ndarray:
    """The tube bent so that its centre line becomes an arc turning by `degrees` about x or y."""
    angle = np.radians(degrees)
    if abs(angle) < 1e-12:
        return vertices.copy()
    bend_radius = length / angle
    u = vertices[:, 0] if axis == "y" else vertices[:, 1]   # offset in the bending plane
    z = vertices[:, 2]
    theta = z / bend_radius
    new_u = (bend_radius - (bend_radius - u) * np.cos(theta))
    new_z = (bend_radius - u) * np.sin(theta)
    bent = vertices.copy()
    bent[:, 2] = new_z
    if axis == "y":
        bent[:, 0] = new_u
    else:
        bent[:, 1] = new_u
    return bent


def grid(size: int = 20, extent: float = 1.0):
    """(size*size by 3 vertices, triangles) of a flat square grid in the xy plane, z = 0."""
    xs = np.linspace(0.0, extent, size)
    vertices = np.array([[x, y, 0.0] for y in xs for x in xs])
    faces = []
    for row in range(size - 1):
        for col in range(size - 1):
            a = row * size + col
            faces += [[a, a + 1, a + size + 1], [a, a + size + 1, a + size]]
    return vertices, np.array(faces)


def bump(vertices: np.ndarray, center, height: float, width: float) -> np.ndarray:
    """The vertices raised along z by a Gaussian bump (height at `center` in xy, std. dev. `width`)."""
    moved = vertices.copy()
    distance2 = ((vertices[:, :2] - np.asarray(center)) ** 2).sum(axis=1)
    moved[:, 2] += height * np.exp(-distance2 / (2 * width ** 2))
    return moved


def write_obj(path: pathlib.Path, vertices: np.ndarray, faces: np.ndarray) -> pathlib.Path:
    """Write a triangle mesh as OBJ (1-based indices); returns the path."""
    lines = [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_tube_set(folder: pathlib.Path, rings: int = 12, segments: int = 10) -> Dict[str, object]:
    """Write rest.obj and bent examples (example_1.obj: 90 degrees about y, example_2.obj: about x).

    Returns {"rest": path, "examples": [paths], "vertices": rest array, "faces": array,
    "bottom": bottom ring indices, "top": top ring indices}.
    """
    folder.mkdir(parents=True, exist_ok=True)
    vertices, faces = tube(rings, segments)
    examples = [bend(vertices, 90, "y"), bend(vertices, 90, "x")]
    paths = [write_obj(folder / f"example_{i + 1}.obj", v, faces) for i, v in enumerate(examples)]
    return {"rest": write_obj(folder / "rest.obj", vertices, faces), "examples": paths, "vertices": vertices,
            "example_vertices": examples, "faces": faces, "bottom": list(range(segments)),
            "top": list(range(len(vertices) - segments, len(vertices)))}


def tube_constraints(tube_set: Dict[str, object], frames: int = 4, top_degrees: Sequence[float] = None) -> Dict:
    """A constraint document for a tube set: bottom ring held, top ring following bends about y.

    Frame k places the top ring where a bend by top_degrees[k] (default evenly 0..80) puts it.
    """
    vertices, top = tube_set["vertices"], tube_set["top"]
    degrees = list(top_degrees) if top_degrees is not None else list(np.linspace(0, 80, frames))
    frame_list: List[Dict] = []
    for k, angle in enumerate(degrees):
        frame_list.append({"name": f"{k + 1:04d}", "targets": {"top": bend(vertices, angle, "y")[top].tolist()}})
    return {"format": "meshik-constraints", "version": 1, "rest": "rest.obj",
            "examples": ["example_1.obj", "example_2.obj"],
            "handles": {"bottom": tube_set["bottom"], "top": top}, "frames": frame_list}


def write_constraints(path: pathlib.Path, document: Dict) -> pathlib.Path:
    """Write a constraint document as JSON; returns the path."""
    path.write_text(json.dumps(document, indent=1))
    return path
