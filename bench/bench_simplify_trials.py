"""Trials towards issue 29's floor (run by `make bench`; alone: run_bench.py --only bench_simplify_trials).

bench_simplify measures the default `--simplify` on the 48-frame horse gallop; this measures two
changes that were tried to bring every frame's worst deviation within 1.5x the rest pose's own
simplification error, on every 4th frame (12 frames), per size (0.5, 0.25, 0.1 of the triangles,
and 4,000):
  - fast-simplification's aggressiveness (`agg`, 7 by default, then 3 and 2): the rest error is the
    example set simplified alone with the same aggressiveness, and the triangle count reached is shown
    (a low aggressiveness stops short of the target);
  - per-frame quadric placement: the default's connectivity kept, every simplified vertex moved in
    each frame to the minimum of the error quadric of the full frame's triangles around the vertices
    merged into it (handles held; a pull of 1e-3 of the quadric's mean eigenvalue towards the
    default's position), for both simplifiers. "rest err" is the default simplifier's on the rest
    alone, unplaced; "placed rest" the same rest simplification with its rest placed alike.
Deviation as in bench_simplify (MeshLab's Hausdorff sampler, 20,000 samples both ways, / the full
frame's bounding-box diagonal). Informational: the exit status is 0 whatever the ratios.
"""
import sys

import numpy as np

from bench_pipeline import gallop_data
from bench_simplify import FLOOR_RATIO, SIZES, deviations, gallop_animation, triangle_target

FRAME_STEP = 4
AGGRESSIVENESS = (7.0, 3.0, 2.0)
PLACEMENT_PULL = 1e-3


def main() -> int:
    """Both trial tables."""
    folders = gallop_data(__doc__, "bench_simplify_trials")
    if folders is None:
        return 0
    meshes, resolved, _, full = gallop_animation(folders)
    frames = full.vertices[::FRAME_STEP]
    print(f"horse gallop, frames {resolved.frame_names[0]}, every {FRAME_STEP}th ({len(frames)} frames); worst / median "
          f"frame's worst deviation, ratio = worst / rest err (floor {FLOOR_RATIO}x)")
    print(f"{'trial':<22} {'size':>6} {'tris':>6} {'rest err':>9} {'worst':>8} {'median':>8} {'ratio':>6} {'placed rest':>11}")
    for size in SIZES:
        for aggressiveness in AGGRESSIVENESS:
            aggressiveness_row(meshes, resolved.handles, frames, size, aggressiveness)
    for method in ("fast", "openmesh"):
        for size in SIZES:
            placement_row(meshes, resolved.handles, frames, size, method)
    return 0


def aggressiveness_row(meshes, handles, frames, size, aggressiveness: float) -> None:
    """Prints the default's deviation with fast-simplification at this aggressiveness."""
    from meshik.posing.simplify import simplify, simplify_animation

    target = triangle_target(size, len(meshes.faces))
    alone = simplify(meshes, target, handles, "fast", aggressiveness=aggressiveness)
    rest_error = deviations([alone.meshes.rest], alone.meshes.faces, [meshes.rest], meshes.faces)[0, 1]
    simplified, default = simplify_animation(meshes, frames, target, handles, "fast", aggressiveness=aggressiveness)
    worst = deviations(default, simplified.meshes.faces, frames, meshes.faces)[:, 1]
    print_row(f"fast agg {aggressiveness:g}", size, len(simplified.meshes.faces), rest_error, worst)


def placement_row(meshes, handles, frames, size, method: str) -> None:
    """Prints the default's deviation with every frame's vertices re-placed by the full frame's quadrics."""
    from meshik.posing.simplify import remap_handles, simplify, simplify_animation

    target = triangle_target(size, len(meshes.faces))
    alone = simplify(meshes, target, handles, method)
    rest_error = deviations([alone.meshes.rest], alone.meshes.faces, [meshes.rest], meshes.faces)[0, 1]
    alone_pins, _ = remap_handles(alone, handles)
    placed_rest = quadric_placement(meshes.rest, meshes.faces, alone.vertex_map, alone.meshes.rest, alone_pins)
    placed_rest_error = deviations([placed_rest], alone.meshes.faces, [meshes.rest], meshes.faces)[0, 1]
    simplified, default = simplify_animation(meshes, frames, target, handles, method)
    pins, _ = remap_handles(simplified, handles)
    placed = [quadric_placement(frame, meshes.faces, simplified.vertex_map, start, pins)
              for frame, start in zip(frames, default)]
    worst = deviations(placed, simplified.meshes.faces, frames, meshes.faces)[:, 1]
    print_row(f"{method} placed", size, len(simplified.meshes.faces), rest_error, worst, placed_rest_error)


def quadric_placement(pose: np.ndarray, faces: np.ndarray, vertex_map: np.ndarray, start: np.ndarray,
                      pinned: np.ndarray) -> np.ndarray:
    """#S by 3: each simplified vertex at the minimum of its area-weighted plane quadric in `pose`.

    pose: #V by 3 full positions; faces: #F by 3; vertex_map: #V full -> simplified vertex; start:
    #S by 3 positions pulled towards (PLACEMENT_PULL) and kept for the #K `pinned` vertices.
    """
    from meshik.posing.simplify import _patch_pairs

    corners = pose[faces]
    twice_area_normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    twice_area = np.linalg.norm(twice_area_normal, axis=1)
    normal = twice_area_normal / np.where(twice_area > 0, twice_area, 1.0)[:, None]
    offset = -np.einsum("ij,ij->i", normal, corners[:, 0])
    vertex, face = _patch_pairs(faces, vertex_map).T
    matrix = np.zeros((len(start), 3, 3))
    rhs = np.zeros((len(start), 3))
    np.add.at(matrix, vertex, twice_area[face, None, None] * normal[face, :, None] * normal[face, None, :])
    np.add.at(rhs, vertex, -(twice_area[face] * offset[face])[:, None] * normal[face])
    pull = PLACEMENT_PULL * np.trace(matrix, axis1=1, axis2=2) / 3.0
    placed = np.linalg.solve(matrix + pull[:, None, None] * np.eye(3), (rhs + pull[:, None] * start)[:, :, None])[:, :, 0]
    placed[pinned] = start[pinned]
    return placed


def print_row(trial: str, size, triangles: int, rest_error: float, worst: np.ndarray, placed_rest=None) -> None:
    """One table row; worst: each frame's worst deviation."""
    placed = f"{placed_rest:>11.5f}" if placed_rest is not None else f"{'':>11}"
    print(f"{trial:<22} {size:>6g} {triangles:>6} {rest_error:>9.5f} {worst.max():>8.5f} {np.median(worst):>8.5f} "
          f"{worst.max() / rest_error:>5.2f}x {placed}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
