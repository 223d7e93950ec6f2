"""MeshLab plugin in pymeshlab: the pose filter's first run on the horse (precompute the examples,
factor G'^T G', solve) against re-runs with the same rest layer, examples and handles but moved
handles (only the solve), and against a run with a new handle set (examples reused, new factor).

Usage: python bench/bench_plugin_reuse.py --samples DIR --data DIR [--plugin FILE] [--runs N]
Prints a table of wall times of `apply_filter` (including pymeshlab's own work per call).
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


def horse_files(data: pathlib.Path):
    """(reference.obj, [1.obj ... 10.obj]) of the shared horse poses."""
    folder = data / "horse-poses"
    examples = sorted((p for p in folder.glob("*.obj") if p.stem.isdigit()), key=lambda p: int(p.stem))
    return folder / "reference.obj", examples


def select(ms: pymeshlab.MeshSet, indices) -> None:
    """Selects exactly `indices` on the current layer."""
    ms.compute_selection_by_condition_per_vertex(condselect=" || ".join(f"(vi == {i})" for i in indices))


def translation(dy: float) -> np.ndarray:
    """4x4 translation by dy along y."""
    matrix = np.eye(4)
    matrix[1, 3] = dy
    return matrix


def timed_pose(ms: pymeshlab.MeshSet, dy: float):
    """(seconds, filter output) of one pose run moving the selected handles by dy."""
    start = time.perf_counter()
    output = ms.apply_filter(POSE, targetsource="Handle transform", handletransform=translation(dy))
    return time.perf_counter() - start, output


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--samples", default=str(ROOT / "sample_meshes"))
    parser.add_argument("--data", default=str(ROOT.parent / "shared" / "data"))
    parser.add_argument("--plugin", default=str(ROOT / "build" / "plugin" / "double" / "libfilter_meshik.so"))
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    rest_path, example_paths = horse_files(pathlib.Path(args.data))
    if not rest_path.is_file():
        print(f"skipped: {rest_path} not found")
        return 0
    pymeshlab.load_plugin(args.plugin)
    ms = pymeshlab.MeshSet()
    for path in [rest_path, *example_paths]:
        ms.load_new_mesh(str(path))
    ms.set_current_mesh(0)
    vertices = ms.current_mesh().vertex_matrix()
    rng = np.random.default_rng(7)
    first_handles = sorted(rng.choice(len(vertices), 20, replace=False))
    select(ms, first_handles)

    first, output = timed_pose(ms, 0.02)
    assert not output["factorization_reused"]
    reruns = []
    for run in range(args.runs):
        seconds, output = timed_pose(ms, 0.03 + 0.01 * run)
        assert output["factorization_reused"]
        reruns.append(seconds)
    new_handles = []
    for run in range(args.runs):
        ms.set_current_mesh(0)
        select(ms, sorted(rng.choice(len(vertices), 20, replace=False)))
        seconds, output = timed_pose(ms, 0.02)
        assert not output["factorization_reused"]
        new_handles.append(seconds)

    rerun = statistics.median(reruns)
    print(f"horse: {len(vertices)} vertices, {len(example_paths)} examples, 20 handles, nonlinear, "
          f"{output['iterations']} Gauss-Newton iterations in the last run")
    print(f"{'run':<44}{'wall ms':>10}{'vs re-run':>11}")
    print(f"{'first (precompute + factor + solve)':<44}{1e3 * first:>10.1f}{first / rerun:>10.1f}x")
    print(f"{'new handles (factor + solve), median':<44}{1e3 * statistics.median(new_handles):>10.1f}"
          f"{statistics.median(new_handles) / rerun:>10.1f}x")
    print(f"{'re-run, moved handles (solve), median':<44}{1e3 * rerun:>10.1f}{1.0:>10.1f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
