"""Imports MeshIK .glb files with Blender's own glTF importer (bpy from the package registry, run in
its own venv by tests/python/test_glb_blender.py), plays each clip key by key and measures how far
the evaluated mesh is from the solver's frames.

    .venv-blender/bin/python tests/blender/play_glb.py MANIFEST.json RESULT.json

MANIFEST.json: [{"glb": path, "frames": path of a .npy, #keys by #V by 3 solver frames in the
file's (glTF) coordinates}, ...]. RESULT.json: one entry per file, {"glb", "imported": bool,
"error": the importer's message when refused, "keys": [...], "slider_ranges": [[min, max] per
shape key], "key_distances": per key the two-sided nearest-vertex distance (the larger of: the
farthest evaluated vertex from the frame's vertices, the farthest frame vertex from the evaluated
ones), "static_distance" (a file without animations): the same for the mesh as imported (its
default weights) against frame 0, "vertices": evaluated vertex count}. Blender is Z-up: glTF (x, y, z) = Blender (x, z, -y).
"""
import json
import sys

import bpy
import numpy as np
from mathutils import kdtree


def main(manifest_path: str, result_path: str) -> int:
    """Plays every file of the manifest; writes the result; 0 unless the script itself failed."""
    results = [play(entry["glb"], np.load(entry["frames"])) for entry in json.load(open(manifest_path))]
    with open(result_path, "w") as out:
        json.dump(results, out)
    return 0


def play(glb: str, frames: np.ndarray) -> dict:
    """The result entry of one file: import it into an empty scene, then evaluate it without its
    animation and at each key. frames: #keys by #V by 3."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    try:
        bpy.ops.import_scene.gltf(filepath=glb)
    except RuntimeError as error:
        return {"glb": glb, "imported": False, "error": str(error).strip().splitlines()[-1]}
    mesh_object = next(o for o in bpy.context.scene.objects if o.type == "MESH")
    key = mesh_object.data.shape_keys
    sliders = [[block.slider_min, block.slider_max] for block in key.key_blocks[1:]]
    if key.animation_data is None:  # a file without its animation: the mesh's default weights
        static = evaluated_vertices(mesh_object)
        return {"glb": glb, "imported": True, "keys": 0, "slider_ranges": sliders, "key_distances": [],
                "static_distance": two_sided_distance(static, frames[0]), "vertices": len(static)}
    action = key.animation_data.action
    key_frames = sorted({point.co.x for curve in fcurves_of(action) for point in curve.keyframe_points})
    distances, count = [], 0
    for k, frame in enumerate(key_frames):
        whole = int(np.floor(frame))
        bpy.context.scene.frame_set(whole, subframe=frame - whole)
        played = evaluated_vertices(mesh_object)
        distances.append(two_sided_distance(played, frames[k]))
        count = len(played)
    return {"glb": glb, "imported": True, "keys": len(key_frames), "slider_ranges": sliders,
            "key_distances": distances, "vertices": count}


def fcurves_of(action):
    """Every F-curve of a (layered, Blender 4.4+) action."""
    return [curve for layer in action.layers for strip in layer.strips for bag in strip.channelbags
            for curve in bag.fcurves]


def evaluated_vertices(mesh_object) -> np.ndarray:
    """#V by 3 world positions of the evaluated mesh (shape keys mixed), in glTF axes."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = mesh_object.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    local = np.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", local)
    matrix = np.array(evaluated.matrix_world)
    evaluated.to_mesh_clear()
    world = local.reshape(-1, 3) @ matrix[:3, :3].T + matrix[:3, 3]
    return np.c_[world[:, 0], world[:, 2], -world[:, 1]]


def two_sided_distance(a: np.ndarray, b: np.ndarray) -> float:
    """The larger of the farthest point of a from its nearest in b and the reverse (#A by 3, #B by 3)."""
    return max(farthest_from(a, b), farthest_from(b, a))


def farthest_from(points: np.ndarray, cloud: np.ndarray) -> float:
    """max over points of the distance to the nearest point of cloud (Blender's KD-tree)."""
    tree = kdtree.KDTree(len(cloud))
    for index, point in enumerate(cloud):
        tree.insert(point.tolist(), index)
    tree.balance()
    return max(tree.find(point.tolist())[2] for point in points)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
