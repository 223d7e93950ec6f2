"""Held-out poses: how close MeshIK gets to poses that were never examples (run by `make bench`
with --samples DIR --data DIR; issue 28).

Protocol (../shared/data): the horse (examples = horse-poses 1-10, targets = the handle positions
of held-out horse-gallop frames, every FRAME_STEP-th) and the elephant (examples = poses 1-4,
targets from the held-out poses 5-10). Handles: 6, 12 and 24 vertices by farthest-point sampling
on the rest mesh. Each method poses every target from its handles alone (a solver built once per
handle set, cold start: the linear space's optimum), and the pose is compared with the held-out
mesh. Per row: mean RMS and the largest vertex error over the bounding-box diagonal, triangles
turned over against the ground truth (summed over the targets), and milliseconds per pose (mean).
Methods: linear (the linear feature space), affine (today's nonlinear space), free (the paper's
free stretch blend), regions 2/4/8/auto (spatially varying weights, affine blend).
The floors of issue 28 are checked against affine in the same run and printed under the table.
"""
import argparse
import pathlib
import time

import numpy as np

import meshik
from meshik.inputs.meshio import load_example_set, load_mesh
from meshik.inputs.tracking import farthest_point_handles

HANDLE_COUNTS = (6, 12, 24)
FRAME_STEP = 6
METHODS = {
    "linear": dict(feature_space="linear"),
    "affine": dict(),
    "free": dict(blend="free"),
    "regions 2": dict(regions=2),
    "regions 4": dict(regions=4),
    "regions 8": dict(regions=8),
    "regions auto": dict(regions="auto"),
}


def problems(data: pathlib.Path):
    """(name, rest path, example paths, held-out target paths) for each available set."""
    horse, gallop, elephant = data / "horse-poses", data / "horse-gallop", data / "elephant-poses"
    if horse.is_dir() and gallop.is_dir():
        frames = sorted(gallop.glob("*.obj"))[::FRAME_STEP]
        yield "horse gallop", horse / "reference.obj", [horse / f"{k}.obj" for k in range(1, 11)], frames
    if elephant.is_dir():
        yield ("elephant", elephant / "reference.obj", [elephant / f"{k}.obj" for k in range(1, 5)],
               [elephant / f"{k}.obj" for k in range(5, 11)])


def inverted_against(posed: np.ndarray, truth: np.ndarray, faces: np.ndarray) -> int:
    """Triangles whose normal in posed (#V by 3) points away from their normal in truth."""
    def normals(v):
        return np.cross(v[faces[:, 1]] - v[faces[:, 0]], v[faces[:, 2]] - v[faces[:, 0]])
    return int(np.count_nonzero(np.einsum("ij,ij->i", normals(posed), normals(truth)) < 0.0))


def measure(example_set, faces, diagonal, handles, targets, options):
    """Poses every target with one solver; returns (mean RMS, max error, inverted, ms per pose)."""
    solver = meshik.Solver.from_example_set(example_set, handles, **options)
    rms, worst, inverted, seconds = [], 0.0, 0, 0.0
    for truth in targets:
        start = time.perf_counter()
        result = solver.solve(truth[handles])
        seconds += time.perf_counter() - start
        error = np.linalg.norm(result.vertices - truth, axis=1) / diagonal
        rms.append(float(np.sqrt(np.mean(error ** 2))))
        worst = max(worst, float(error.max()))
        inverted += inverted_against(result.vertices, truth, faces)
    return float(np.mean(rms)), worst, inverted, 1000.0 * seconds / len(targets)


def check_floors(name, rows):
    """Prints issue 28's floors for one mesh's rows {(handles, method): (rms, max, inverted, ms)}."""
    lines = []
    for count in HANDLE_COUNTS:
        affine_rms, _, _, affine_ms = rows[(count, "affine")]
        free_rms = rows[(count, "free")][0]
        lines.append(f"{name}, {count} handles: free / affine RMS = {free_rms / affine_rms:.3f} "
                     f"({'met' if free_rms <= 1.01 * affine_rms else 'NOT met'}: <= 1.01)")
        for method in METHODS:
            if not method.startswith("regions"):
                continue
            rms, _, _, ms = rows[(count, method)]
            verdicts = [f"RMS {rms / affine_rms:.3f} x affine ({'met' if rms <= 1.02 * affine_rms else 'NOT met'}: <= 1.02"]
            if name == "horse gallop" and count in (12, 24):
                verdicts[-1] += f"; {'met' if rms <= 0.8 * affine_rms else 'NOT met'}: <= 0.80 here"
            verdicts[-1] += ")"
            verdicts.append(f"time {ms / affine_ms:.2f} x affine ({'met' if ms <= 3.0 * affine_ms else 'NOT met'}: <= 3)")
            lines.append(f"{name}, {count} handles, {method}: " + ", ".join(verdicts))
    return lines


def main() -> int:
    """Print the table and the floors; exit status 0 (numbers for reading)."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=pathlib.Path, help="sample_meshes/ (unused here)")
    parser.add_argument("--data", type=pathlib.Path, required=True, help="../shared/data")
    parser.add_argument("--methods", default="", help="comma-separated subset of the methods (default: all)")
    args = parser.parse_args()
    methods = [m for m in METHODS if not args.methods or m in args.methods.split(",")]
    print("Held-out poses (issue 28): errors over the bounding-box diagonal, mean RMS over the targets and the "
          "largest vertex error; inverted: triangles turned over against the ground truth, summed over the targets")
    print("| mesh | handles | method | regions | RMS | max | inverted | ms / pose |")
    print("|---|---|---|---|---|---|---|---|")
    floors = []
    for name, rest_path, example_paths, target_paths in problems(args.data):
        meshes = load_example_set(rest_path, example_paths)
        targets = [load_mesh(path)[0] for path in target_paths]
        diagonal = float(np.linalg.norm(meshes.rest.max(axis=0) - meshes.rest.min(axis=0)))
        example_set = meshik.ExampleSet(meshes.rest, meshes.faces, list(meshes.examples))
        rows = {}
        for count in HANDLE_COUNTS:
            handles = farthest_point_handles(meshes.rest, count)
            for method in methods:
                options = METHODS[method]
                rms, worst, inverted, ms = measure(example_set, meshes.faces, diagonal, handles, targets, options)
                regions = meshik.Solver.from_example_set(example_set, handles, **options).num_regions \
                    if method == "regions auto" else options.get("regions", 1)
                rows[(count, method)] = (rms, worst, inverted, ms)
                print(f"| {name} ({len(targets)} targets) | {count} | {method} | {regions} | {rms:.5f} | {worst:.4f} "
                      f"| {inverted} | {ms:.1f} |", flush=True)
        if all(m in methods for m in METHODS):
            floors += check_floors(name, rows)
    for line in floors:
        print(line)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
