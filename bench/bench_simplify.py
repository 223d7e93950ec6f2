"""Simplified animations benchmark (run by `make bench` with --samples DIR --data DIR).

The 48-frame horse gallop (12 tracked handle vertices, horse-poses 1-10 as examples) posed at full
resolution once, then for each simplifier (fast, openmesh) and size (0.5, 0.25, 0.1 of the
triangles, and 4,000 triangles as in issue 29) both ways the pipeline offers:
  - default: the full-resolution frames simplified together with the example set (simplify_animation);
  - simplify first: the simplified example set posed directly.
Printed per row: the rest pose's own simplification error (the rest of each way's simplified mesh:
the example set alone, and the example set with the frames), each way's mean and worst deviation
from the full animation (MeshLab's Hausdorff sampler, 20,000 samples, both ways, as a fraction of
each full frame's bounding-box diagonal; mean: over frames of the mean distance), the median frame's
worst, the time per frame of each way (default: the full solve plus simplifying the frame; simplify
first: the simplified solve) and the handles' distance from their targets on the default frames.
Floor: with the default, every frame's worst deviation is at most 1.5x the rest pose's own error at
the same size (the smaller of the two), and every handle not merged into another stays on its target; exit status 1 if not.
"""
import pathlib
import sys
import tempfile
import time

import numpy as np

from bench_pipeline import gallop_constraints, gallop_data

SIZES = (0.5, 0.25, 0.1, 4000)
SIMPLIFIERS = ("fast", "openmesh")
SAMPLES = 20000
FLOOR_RATIO = 1.5


def main() -> int:
    """The table; exit status 1 when a row misses the floor."""
    folders = gallop_data(__doc__, "bench_simplify")
    if folders is None:
        return 0
    meshes, resolved, options, full = gallop_animation(folders)
    print(f"horse gallop: {len(resolved.frame_names)} frames, {len(meshes.faces)} triangles, {len(resolved.handles)} "
          f"handles, {len(meshes.examples)} examples; full-resolution solve {1e3 * full.solve_seconds.mean():.2f} ms "
          f"per frame. Deviation from the full frame / its bbox diagonal, {SAMPLES} samples both ways.")
    print(f"{'simplifier':<10} {'size':>6} {'tris':>6} {'rest err':>17} | {'default: mean':>13} {'median':>7} "
          f"{'worst':>7} {'ms/frame':>8} | {'first: mean':>11} {'median':>7} {'worst':>7} {'ms/frame':>8} | "
          f"{'handle':>7} {'merged':>6} {'floor':>5}")
    ok = True
    for method in SIMPLIFIERS:
        for size in SIZES:
            ok &= bench_row(meshes, resolved, options, full, method, size)
    return 0 if ok else 1


def gallop_animation(folders):
    """(example set, resolved constraints, solver options, full-resolution PosedAnimation) of the gallop.

    folders: (horse-poses, horse-gallop) as gallop_data returns them.
    """
    from meshik.inputs import constraints
    from meshik.inputs.meshio import load_example_set
    from meshik.posing.animation import pose_animation

    with tempfile.TemporaryDirectory(prefix="meshik-bench-") as scratch:
        constraint_set = constraints.load(gallop_constraints(*folders, pathlib.Path(scratch)))
    meshes = load_example_set(constraint_set.rest, constraint_set.examples)
    resolved = constraints.resolve(constraint_set, meshes.rest)
    options = dict({"feature_space": "nonlinear"}, **constraint_set.solver_options())
    return meshes, resolved, options, pose_animation(meshes, resolved.handles, resolved.targets, options)


def bench_row(meshes, resolved, options, full, method: str, size) -> bool:
    """One row of the table; returns whether the default meets the floor (and the handles their targets)."""
    from meshik.posing.animation import pose_animation
    from meshik.posing.simplify import remap_handles, simplify, simplify_animation

    target = triangle_target(size, len(meshes.faces))
    start = time.perf_counter()
    simplified, default = simplify_animation(meshes, full.vertices, target, resolved.handles, method)
    carry_seconds = (time.perf_counter() - start) / len(default)
    alone = simplify(meshes, target, resolved.handles, method)
    handles, kept = remap_handles(alone, resolved.handles)
    first = pose_animation(alone.meshes, handles, resolved.targets[:, kept], options)

    faces = simplified.meshes.faces
    rest_errors = [deviations([s.meshes.rest], s.meshes.faces, [meshes.rest], meshes.faces)[0][1]
                   for s in (alone, simplified)]
    rest_error = min(rest_errors)
    default_dev = deviations(default, faces, full.vertices, meshes.faces)
    first_dev = deviations(first.vertices, alone.meshes.faces, full.vertices, meshes.faces)
    diagonal = np.linalg.norm(np.ptp(meshes.rest, axis=0))
    handles, kept = remap_handles(simplified, resolved.handles)
    handle_error = np.linalg.norm(default[:, handles] - resolved.targets[:, kept], axis=2).max() / diagonal
    merged = len(resolved.handles) - len(handles)
    meets = bool(default_dev[:, 1].max() <= FLOOR_RATIO * rest_error and handle_error <= 1e-9)
    label = f"{size:g}" if isinstance(size, float) else str(size)
    default_ms = 1e3 * (full.solve_seconds.mean() + carry_seconds)
    print(f"{method:<10} {label:>6} {len(faces):>6} {rest_errors[0]:>8.5f} {rest_errors[1]:>8.5f} | "
          f"{summary(default_dev)} {default_ms:>8.2f} | "
          f"{summary(first_dev, 11)} {1e3 * first.solve_seconds.mean():>8.2f} | {handle_error:>7.1e} {merged:>6} "
          f"{'PASS' if meets else 'FAIL':>5}", flush=True)
    worst = int(np.argmax(default_dev[:, 1]))
    print(f"{'':<10} worst default frame {resolved.frame_names[worst]}: {default_dev[worst, 1]:.5f} = "
          f"{default_dev[worst, 1] / rest_error:.2f}x the rest error (floor {FLOOR_RATIO}x); worst simplify-first frame "
          f"{resolved.frame_names[int(np.argmax(first_dev[:, 1]))]}; simplifying a frame {1e3 * carry_seconds:.2f} ms")
    return meets


def triangle_target(size, triangles: int) -> int:
    """The triangle count a size asks for: an int as is, a fraction of `triangles` rounded."""
    return size if isinstance(size, int) else int(round(size * triangles))


def deviations(simplified_frames, faces, full_frames, full_faces) -> np.ndarray:
    """#frames by 2 (mean, worst) deviation of each simplified frame from its full frame, / the full
    frame's bbox diagonal. simplified_frames: #frames by #S by 3 on faces; full_frames: #frames by #V by 3."""
    from meshik.inputs.meshio import surface_deviation

    rows = []
    for simplified, original in zip(simplified_frames, full_frames):
        diagonal = np.linalg.norm(np.ptp(original, axis=0))
        rows.append(np.array(surface_deviation(simplified, faces, original, full_faces, SAMPLES)) / diagonal)
    return np.array(rows)


def summary(deviation: np.ndarray, width: int = 13) -> str:
    """'mean median-frame-worst worst-frame' columns of a #frames by 2 deviation table."""
    return f"{deviation[:, 0].mean():>{width}.5f} {np.median(deviation[:, 1]):>7.4f} {deviation[:, 1].max():>7.4f}"


if __name__ == "__main__":
    sys.exit(main())
