"""Constraint documents that follow a reference animation at a few handle vertices.

Given meshes of an existing animation (same vertices as the rest mesh), write a constraint file
whose handles track those vertices frame by frame; posing it with MeshIK then reconstructs the
animation from the handles alone, and the reference frames measure how well it does.
"""
import os
from pathlib import Path
from typing import Dict, List, Sequence

import numpy as np

from meshik.inputs.constraints import FORMAT_NAME, FORMAT_VERSION


def farthest_point_handles(vertices: np.ndarray, count: int, start: int = 0) -> np.ndarray:
    """`count` vertex indices spread over the mesh: greedy farthest-point sampling from `start`.

    vertices: #V by 3. Returns #count distinct indices (deterministic).
    """
    chosen = [start]
    distance = np.linalg.norm(vertices - vertices[start], axis=1)
    for _ in range(count - 1):
        chosen.append(int(np.argmax(distance)))
        distance = np.minimum(distance, np.linalg.norm(vertices - vertices[chosen[-1]], axis=1))
    return np.array(chosen)


def tracking_document(constraints_path, rest_path, example_paths: Sequence, frames: Dict[str, np.ndarray],
                      handles: np.ndarray, group: str = "tracked", fps: float = 24.0) -> Dict:
    """A version-1 constraint document: one handle group `handles` following `frames`.

    constraints_path: where the document will be written (mesh paths are made relative to it);
    frames: frame name -> #V by 3 positions of the reference animation.
    """
    folder = Path(constraints_path).resolve().parent
    relative = lambda path: os.path.relpath(Path(path).resolve(), folder)  # noqa: E731
    handles = [int(h) for h in handles]
    frame_list: List[Dict] = [{"name": name, "targets": {group: np.asarray(positions)[handles].tolist()}}
                              for name, positions in frames.items()]
    return {"format": FORMAT_NAME, "version": FORMAT_VERSION, "rest": relative(rest_path),
            "examples": [relative(p) for p in example_paths], "fps": fps, "handles": {group: handles}, "frames": frame_list}
