"""MeshLab plugin in pymeshlab: the pose filter's first run on the horse (precompute the examples,
factor G'^T G', solve) against re-runs with the same rest layer, examples and handles and new
targets (only the solve), and against runs with a new handle set (examples reused, new factor).
The targets are the handles' positions in frames of the horse gallop (target layers).

Usage: python bench/bench_plugin_reuse.py --samples DIR --data DIR [--plugin FILE] [--runs N]
Prints a table of wall times of `apply_filter` (including pymeshlab's and the plugin's per-call
work: reading the layers, writing the pose layer).
"""
import argparse
import pathlib
import statistics
import sys
import time

import numpy as np
import pymeshlab

ROOT = pathlib.Path(__file__).resolve().parent.parent
POSE = "compute_coord_meshik_pose"


def numbered_files(folder: pathlib.Path):
    """(reference.obj, [1.obj, 2.obj, ...]) of a shared-data folder, in numeric order."""
    numbered = sorted((p for p in folder.glob("*.obj") if p.stem.isdigit()), key=lambda p: int(p.stem))
    return folder / "reference.obj", numbered


def select(ms: pymeshlab.MeshSet, indices) -> None:
    """Selects exactly `indices` on the current layer."""
    ms.compute_selection_by_condition_per_vertex(condselect=" || ".join(f"(vi == {i})" for i in indices))


def timed_pose(ms: pymeshlab.MeshSet, examples: str, target: int):
    """(seconds, filter output) of one pose run with the handles' targets in layer `target`."""
    start = time.perf_counter()
    output = ms.apply_filter(POSE, examplelayers=examples, targetsource="Target layer", targetmesh=target)
    return time.perf_counter() - start, output


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--samples", default=str(ROOT / "sample_meshes"))
    parser.add_argument("--data", default=str(ROOT.parent / "shared" / "data"))
    parser.add_argument("--plugin", default=str(ROOT / "build" / "plugin" / "double" / "libfilter_meshik.so"))
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    rest_path, example_paths = numbered_files(pathlib.Path(args.data) / "horse-poses")
    _, gallop_paths = numbered_files(pathlib.Path(args.data) / "horse-gallop")
    if not rest_path.is_file() or len(gallop_paths) < 2 * args.runs + 1:
        print(f"skipped: the horse poses and gallop are not in {args.data}")
        return 0
    pymeshlab.load_plugin(args.plugin)
    ms = pymeshlab.MeshSet()
    for path in [rest_path, *example_paths, *gallop_paths[:2 * args.runs + 1]]:
        ms.load_new_mesh(str(path))
    examples = ", ".join(str(i) for i in range(1, len(example_paths) + 1))
    targets = list(range(len(example_paths) + 1, ms.mesh_number()))
    ms.set_current_mesh(0)
    vertices = ms.current_mesh().vertex_matrix()
    rng = np.random.default_rng(7)
    select(ms, sorted(rng.choice(len(vertices), 20, replace=False)))

    first, output = timed_pose(ms, examples, targets[0])
    assert not output["factorization_reused"]
    reruns, iterations = [], []
    for target in targets[1:args.runs + 1]:
        seconds, output = timed_pose(ms, examples, target)
        assert output["factorization_reused"]
        reruns.append(seconds)
        iterations.append(output["iterations"])
    new_handles = []
    for target in targets[args.runs + 1:]:
        select(ms, sorted(rng.choice(len(vertices), 20, replace=False)))
        seconds, output = timed_pose(ms, examples, target)
        assert not output["factorization_reused"]
        new_handles.append(seconds)

    rerun = statistics.median(reruns)
    print(f"horse: {len(vertices)} vertices, {len(example_paths)} examples, 20 random handles, nonlinear; "
          f"targets from gallop frames; re-runs took {min(iterations)}-{max(iterations)} Gauss-Newton iterations")
    print(f"{'run':<44}{'wall ms':>10}{'vs re-run':>11}")
    print(f"{'first (precompute + factor + solve)':<44}{1e3 * first:>10.1f}{first / rerun:>10.1f}x")
    print(f"{'new handles (factor + solve), median':<44}{1e3 * statistics.median(new_handles):>10.1f}"
          f"{statistics.median(new_handles) / rerun:>10.1f}x")
    print(f"{'re-run, new targets (solve), median':<44}{1e3 * rerun:>10.1f}{1.0:>10.1f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
