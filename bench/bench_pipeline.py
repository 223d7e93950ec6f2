"""Pipeline benchmark (run by `make bench` with --samples DIR --data DIR).

1. The 48-frame horse gallop (12 tracked handle vertices, horse-poses as examples) through load,
   pose and export of .drc and .glb, wall time against the 3 s floor; the pipeline's per-pose
   time against the core's own per-pose time measured in the same run (same solver, handles,
   targets and warm start, no pipeline around it).
2. The two simplifiers on horse-poses (12 handles): time, and the worst distance (symmetric
   Hausdorff, MeshLab's sampler) of each simplified pose from its full-resolution pose.
"""
import argparse
import json
import pathlib
import statistics
import sys
import tempfile
import time

import numpy as np

FLOOR_SECONDS = 3.0
REPEATS = 3


def gallop_data(description: str, name: str):
    """(horse-poses, horse-gallop) folders from the --data argument of run_bench's command line, or
    None (after saying that benchmark `name` is skipped) when they are absent."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=pathlib.Path, help="sample_meshes/ (unused here)")
    parser.add_argument("--data", type=pathlib.Path, required=True, help="../shared/data")
    args = parser.parse_args()
    horse, gallop = args.data / "horse-poses", args.data / "horse-gallop"
    if not (horse.is_dir() and gallop.is_dir()):
        print(f"{name}: skipped, {horse} or {gallop} not found")
        return None
    return horse, gallop


def main() -> int:
    """Both tables; exit status 1 when the gallop misses the floor."""
    folders = gallop_data(__doc__, "bench_pipeline")
    if folders is None:
        return 0
    horse, gallop = folders
    with tempfile.TemporaryDirectory(prefix="meshik-bench-") as scratch:
        ok = bench_gallop(horse, gallop, pathlib.Path(scratch))
    bench_simplifiers(horse)
    return 0 if ok else 1


def horse_files(horse: pathlib.Path):
    """(rest path, example paths 1..10 in numeric order) of horse-poses."""
    examples = sorted((p for p in horse.glob("*.obj") if p.stem.isdigit()), key=lambda p: int(p.stem))
    return horse / "reference.obj", examples


def gallop_constraints(horse: pathlib.Path, gallop: pathlib.Path, scratch: pathlib.Path) -> pathlib.Path:
    """Writes scratch/gallop.json: the gallop's frames tracked by 12 farthest-point handle vertices
    of horse-poses' rest mesh, horse-poses' examples; returns its path."""
    from meshik.inputs.meshio import load_mesh
    from meshik.inputs.tracking import farthest_point_handles, tracking_document

    rest_path, example_paths = horse_files(horse)
    rest, _ = load_mesh(rest_path)
    frames = {p.stem: load_mesh(p)[0] for p in sorted(gallop.glob("*.obj")) if p.stem.isdigit()}
    path = scratch / "gallop.json"
    path.write_text(json.dumps(tracking_document(path, rest_path, example_paths, frames, farthest_point_handles(rest, 12))))
    return path


def bench_gallop(horse: pathlib.Path, gallop: pathlib.Path, scratch: pathlib.Path) -> bool:
    """Table 1; returns whether the end-to-end time is under the floor."""
    from meshik.inputs import constraints
    from meshik.inputs.meshio import load_example_set
    from meshik.pipeline import pose_job

    path = gallop_constraints(horse, gallop, scratch)
    constraint_set = constraints.load(path)
    meshes = load_example_set(constraint_set.rest, constraint_set.examples)
    resolved = constraints.resolve(constraint_set, meshes.rest)
    # pipeline and core alone alternate, so that load from other processes hits both alike
    walls, reports, core_per_pose = [], [], []
    for _ in range(REPEATS):
        start = time.perf_counter()
        reports.append(pose_job(path, scratch / "out", formats=("drc", "glb"), quiet=True, force=True))
        walls.append(time.perf_counter() - start)
        core_per_pose.append(core_solve_times(meshes, resolved))
    best = int(np.argmin(walls))
    report = reports[best]
    pipeline_per_pose = min(r["timings"]["solve_mean"] for r in reports)
    core_per_pose = min(core_per_pose)

    timings = report["timings"]
    print(f"horse gallop: {len(resolved.frame_names)} frames, {len(meshes.rest)} vertices, 12 handle vertices, "
          f"{len(meshes.examples)} examples, best of {REPEATS}")
    print(f"{'stage':<34}{'seconds':>10}")
    for stage in ("load", "precompute", "solve_total", "export", "total"):
        print(f"  {stage:<32}{timings[stage]:>10.3f}")
    print(f"  {'pose_job wall (median)':<32}{statistics.median(walls):>10.3f}")
    verdict = "PASS" if walls[best] < FLOOR_SECONDS else "FAIL"
    print(f"end to end (load, pose, export drc+glb): {walls[best]:.3f} s vs floor {FLOOR_SECONDS:.1f} s: "
          f"{walls[best] / FLOOR_SECONDS:.2f} of the floor  [{verdict}]")
    print(f"per pose: pipeline {1e3 * pipeline_per_pose:.2f} ms, core alone {1e3 * core_per_pose:.2f} ms, "
          f"ratio {pipeline_per_pose / core_per_pose:.3f}")
    print(f"outputs: {sum(report['outputs'].values()) / 1e6:.2f} MB "
          f"({len(report['outputs'])} files), handle fit error {report['handle_fit_error']['max']:.2e}")
    return walls[best] < FLOOR_SECONDS


def core_solve_times(meshes, resolved) -> float:
    """Mean seconds per frame of the core's Solver.solve over the animation, warm-started."""
    import meshik

    solver = meshik.Solver(meshes.rest, meshes.faces, list(meshes.examples), resolved.handles)
    weights, seconds = None, []
    for targets in resolved.targets:
        start = time.perf_counter()
        result = solver.solve(targets, initial_weights=weights)
        seconds.append(time.perf_counter() - start)
        weights = result.weights
    return float(np.mean(seconds))


def bench_simplifiers(horse: pathlib.Path) -> None:
    """Table 2: fast vs openmesh at two targets."""
    from meshik.inputs.meshio import load_example_set, surface_distance
    from meshik.posing.simplify import simplify
    from meshik.inputs.tracking import farthest_point_handles

    rest_path, example_paths = horse_files(horse)
    meshes = load_example_set(rest_path, example_paths)
    handles = farthest_point_handles(meshes.rest, 12)
    diagonal = float(np.linalg.norm(np.ptp(meshes.rest, axis=0)))
    print(f"\nsimplifiers on horse-poses ({len(meshes.faces)} triangles, rest + {len(meshes.examples)} examples, "
          f"12 handles); distance = symmetric Hausdorff of each simplified pose to its full pose, / bbox diagonal")
    print(f"{'target':>8} {'simplifier':<10} {'triangles':>9} {'seconds':>8} {'worst pose':>11} {'mean pose':>10} {'rest':>8}")
    full = (meshes.rest,) + meshes.examples
    for target in (4000, 1000):
        for method in ("fast", "openmesh"):
            start = time.perf_counter()
            result = simplify(meshes, target, handles, method)
            seconds = time.perf_counter() - start
            poses = (result.meshes.rest,) + result.meshes.examples
            distances = [surface_distance(p, result.meshes.faces, f, meshes.faces) / diagonal for p, f in zip(poses, full)]
            print(f"{target:>8} {method:<10} {len(result.meshes.faces):>9} {seconds:>8.3f} {max(distances):>11.5f} "
                  f"{np.mean(distances):>10.5f} {distances[0]:>8.5f}")


if __name__ == "__main__":
    sys.exit(main())
