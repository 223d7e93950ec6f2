"""Mesh files through pymeshlab: load one mesh or a whole example set, save a posed mesh.

pymeshlab reads and writes every format MeshLab knows (OBJ, PLY, OFF, STL, ...). Only numpy
arrays leave this module. pymeshlab is imported on first use, so `import meshik` stays light.
"""
import re
from dataclasses import dataclass
from pathlib import Path
from typing import List, Sequence, Tuple

import numpy as np

from meshik.errors import MeshFileError, OutputError
from meshik.inputs.isolated_load import check_input_file, isolated_load
from meshik.inputs.mesh_values import check_mesh_values
from meshik.inputs.meshlab_module import pymeshlab_module
from meshik.inputs.obj_text import check_obj_vertices
from meshik.outputs.safe_paths import utf8_name

# Attributes MeshLab would add to a saved file that a posed mesh does not have; each one is
# dropped from the request when the format has no such parameter.
_PLAIN_SAVE_OPTIONS = {"save_vertex_color": False, "save_vertex_quality": False, "save_vertex_normal": False,
                       "save_face_color": False, "save_face_quality": False, "save_wedge_texcoord": False,
                       "save_wedge_normal": False}
_UNKNOWN_PARAMETER = re.compile(r"Parameter (\w+) not found")
# The largest coordinate magnitude accepted: products of coordinates (areas, normal matrices)
# must stay far inside float64's range and the single-precision features' (3.4e38).
MAX_COORDINATE = 1e12


@dataclass(frozen=True)
class ExampleMeshes:
    """A rest mesh and its example poses, all with the rest mesh's triangle list.

    rest:     #V by 3 rest positions
    faces:    #F by 3 vertex indices (int64), shared by every pose
    examples: #E arrays, each #V by 3
    """
    rest: np.ndarray
    faces: np.ndarray
    examples: Tuple[np.ndarray, ...]
    rest_path: Path
    example_paths: Tuple[Path, ...]


def load_mesh(path) -> Tuple[np.ndarray, np.ndarray]:
    """(#V by 3 float64 positions, #F by 3 int64 triangles) of a mesh file. Raises MeshFileError.

    The file is read by MeshLab's readers in a forked child process (see isolated_load), since some
    of them crash on malformed files (an OBJ or OFF face index out of range); an OBJ's vertex lines are
    checked first (meshik.inputs.obj_text: the reader reads a garbled coordinate as 0), and every format's
    coordinates are checked for NaN and infinity (meshik.inputs.mesh_values: the readers would drop those
    vertices and shift every later index). Coordinates beyond MAX_COORDINATE are refused.
    """
    path = Path(path)
    check_input_file(path, "mesh file")
    if path.suffix.lower() == ".obj":
        check_obj_vertices(path)
    check_mesh_values(path, path.read_bytes())
    vertices, faces = isolated_load(path)
    if len(faces) == 0:
        raise MeshFileError(f"{path}: the mesh has no triangles")
    far = np.flatnonzero(~(np.abs(vertices) <= MAX_COORDINATE).all(axis=1))
    if len(far):
        raise MeshFileError(f"{path}: vertex {far[0]} has the coordinates {vertices[far[0]].tolist()}, beyond the "
                            f"{MAX_COORDINATE:g} accepted (the features and weights would lose all precision)")
    bad = np.flatnonzero(((faces < 0) | (faces >= len(vertices))).any(axis=1))
    if len(bad):
        raise MeshFileError(f"{path}: triangle {bad[0]} has corners {faces[bad[0]].tolist()} but the mesh has "
                            f"{len(vertices)} vertices")
    return vertices, faces


def load_example_set(rest_path, example_paths: Sequence) -> ExampleMeshes:
    """Load the rest mesh and every example; all must share the rest mesh's vertex count and triangles.

    Raises MeshFileError naming the first file (and triangle) that differs.
    """
    rest_path = Path(rest_path)
    rest, faces = load_mesh(rest_path)
    examples: List[np.ndarray] = []
    for path in map(Path, example_paths):
        vertices, example_faces = load_mesh(path)
        _check_same_topology(path, vertices, example_faces, rest_path, rest, faces)
        examples.append(vertices)
    return ExampleMeshes(rest=rest, faces=faces, examples=tuple(examples), rest_path=rest_path,
                         example_paths=tuple(map(Path, example_paths)))


def _check_same_topology(path: Path, vertices: np.ndarray, faces: np.ndarray,
                         rest_path: Path, rest: np.ndarray, rest_faces: np.ndarray) -> None:
    """MeshFileError unless an example has the rest mesh's vertex count and identical triangle list.

    When the rest mesh has fewer vertices or triangles than the example, MeshLab may have dropped
    some of the rest's while reading (non-finite coordinates, a triangle with a repeated corner):
    the message points at the rest mesh too.
    """
    if len(vertices) > len(rest):
        raise MeshFileError(f"{path}: has {len(vertices)} vertices but the rest mesh {rest_path} has {len(rest)}; every "
                            "example must have the rest mesh's vertices (MeshLab drops vertices with NaN or infinite "
                            f"coordinates when reading: if {rest_path} has such vertices, fix them there)")
    if len(faces) > len(rest_faces) and len(vertices) == len(rest):
        first = int(np.argmax(np.append((faces[:len(rest_faces)] != rest_faces).any(axis=1), True)))
        raise MeshFileError(f"{rest_path}: triangle {first} could not be read (MeshLab drops triangles with a repeated "
                            f"corner or a vertex with NaN or infinite coordinates), so the rest mesh has "
                            f"{len(rest_faces)} triangles but the example {path} has {len(faces)}")
    if len(vertices) != len(rest):
        hint = " (MeshLab drops vertices with NaN or infinite coordinates when loading)" if len(vertices) < len(rest) else ""
        raise MeshFileError(f"{path}: has {len(vertices)} vertices but the rest mesh {rest_path} has {len(rest)}{hint}; "
                            "every example must have the rest mesh's vertices and triangles")
    if len(faces) != len(rest_faces):
        raise MeshFileError(f"{path}: has {len(faces)} triangles but the rest mesh {rest_path} has {len(rest_faces)}; "
                            "every example must have the rest mesh's triangle list")
    differs = np.flatnonzero((faces != rest_faces).any(axis=1))
    if len(differs):
        first = differs[0]
        raise MeshFileError(f"{path}: triangle {first} is {faces[first].tolist()} but in the rest mesh {rest_path} "
                            f"it is {rest_faces[first].tolist()}; every example must have the rest mesh's triangle list")


def save_mesh(path, vertices: np.ndarray, faces: np.ndarray) -> None:
    """Write a mesh (#V by 3 positions, #F by 3 triangles) in the format of `path`'s extension.

    Only positions and triangles are written (no colours, normals or quality). Raises OutputError
    for a format pymeshlab cannot write.
    """
    pymeshlab = pymeshlab_module()

    utf8_name(path, OutputError)
    if not np.isfinite(vertices).all():
        raise OutputError(f"{path}: refusing to write a mesh with non-finite coordinates")
    meshes = pymeshlab.MeshSet()
    meshes.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(vertices, dtype=np.float64),
                                   face_matrix=np.asarray(faces, dtype=np.int32)))
    options = dict(_PLAIN_SAVE_OPTIONS)
    while True:
        try:
            meshes.save_current_mesh(str(path), **options)
            return
        except pymeshlab.PyMeshLabException as error:
            unknown = _UNKNOWN_PARAMETER.search(str(error))
            if unknown is None or unknown.group(1) not in options:
                raise OutputError(f"{path}: cannot write the mesh: {' '.join(str(error).split())}") from None
            del options[unknown.group(1)]


def surface_distance(vertices_a: np.ndarray, faces_a: np.ndarray, vertices_b: np.ndarray, faces_b: np.ndarray,
                     samples: int = 100000) -> float:
    """Symmetric Hausdorff distance between two triangle meshes (#V by 3 positions, #F by 3 each).

    MeshLab's sampler: every vertex plus points on edges and faces (about `samples` per mesh),
    each measured to the nearest point of the other surface; returns the largest distance.
    """
    return surface_deviation(vertices_a, faces_a, vertices_b, faces_b, samples)[1]


def surface_deviation(vertices_a: np.ndarray, faces_a: np.ndarray, vertices_b: np.ndarray, faces_b: np.ndarray,
                      samples: int = 100000) -> Tuple[float, float]:
    """(mean, max) distance between two triangle meshes (#V by 3 positions, #F by 3 each), both ways.

    MeshLab's Hausdorff sampler run from each mesh to the other (about `samples` points per mesh):
    max is the symmetric Hausdorff distance, mean the average of the two directions' mean distances.
    """
    pymeshlab = pymeshlab_module()

    meshes = pymeshlab.MeshSet()
    for vertices, faces in ((vertices_a, faces_a), (vertices_b, faces_b)):
        meshes.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(vertices, dtype=np.float64),
                                       face_matrix=np.asarray(faces, dtype=np.int32)))
    means, worst = [], 0.0
    for sampled, target in ((0, 1), (1, 0)):
        result = meshes.get_hausdorff_distance(sampledmesh=sampled, targetmesh=target, samplevert=True, sampleedge=True,
                                               sampleface=True, samplenum=samples, maxdist=pymeshlab.PercentageValue(100))
        means.append(result["mean"])
        worst = max(worst, result["max"])
    return float(np.mean(means)), worst


def saveable_format(extension: str) -> bool:
    """Whether pymeshlab can write meshes with this file extension (without the dot, e.g. "ply")."""
    pymeshlab = pymeshlab_module()

    probe = pymeshlab.MeshSet()
    probe.add_mesh(pymeshlab.Mesh(vertex_matrix=np.eye(3), face_matrix=np.array([[0, 1, 2]], dtype=np.int32)))
    try:
        probe.save_current_mesh(f"/nonexistent-folder/probe.{extension}")
    except pymeshlab.PyMeshLabException as error:
        return "Unknown format" not in str(error)
    return True
