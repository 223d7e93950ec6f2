"""Example-set precompute on one thread and on all cores (run by `make bench` with --samples DIR --data DIR).

For the horse and the elephant (4 examples each, from ../shared/data) the ExampleSet is built
alternately with threads=1 and threads=None (all cores), REPEATS times each; the table gives the
medians and their ratio, measured in the same run (the machine is shared: load drifts).
"""
import argparse
import os
import pathlib
import statistics
import time

import meshik
from meshik.inputs.meshio import load_example_set

REPEATS = 5
SETS = {"horse": "horse-poses", "elephant": "elephant-poses"}


def example_files(folder: pathlib.Path):
    """(reference.obj, the poses 1.obj .. 4.obj): the paper's rows use 4 examples."""
    return folder / "reference.obj", [folder / f"{k}.obj" for k in range(1, 5)]


def seconds(meshes, threads) -> float:
    start = time.perf_counter()
    meshik.ExampleSet(meshes.rest, meshes.faces, list(meshes.examples), threads=threads)
    return time.perf_counter() - start


def main() -> int:
    """Print the table; exit status 0 (numbers for reading)."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=pathlib.Path, help="sample_meshes/ (unused here)")
    parser.add_argument("--data", type=pathlib.Path, required=True, help="../shared/data")
    args = parser.parse_args()
    print(f"ExampleSet precompute, 4 examples, medians of {REPEATS} alternating runs, {os.cpu_count()} cores")
    print("| mesh | triangles | 1 thread (ms) | all cores (ms) | ratio all / 1 |")
    print("|---|---|---|---|---|")
    for name, folder in SETS.items():
        if not (args.data / folder).is_dir():
            print(f"| {name} | (no {args.data / folder}) | | | |")
            continue
        rest, examples = example_files(args.data / folder)
        meshes = load_example_set(rest, examples)
        seconds(meshes, None)  # warm-up: first-touch allocations and the OpenMP team
        runs = {1: [], None: []}
        for _ in range(REPEATS):
            for threads in runs:
                runs[threads].append(seconds(meshes, threads))
        one, all_cores = statistics.median(runs[1]), statistics.median(runs[None])
        print(f"| {name} | {len(meshes.faces):,} | {1000 * one:.0f} | {1000 * all_cores:.0f} | {all_cores / one:.2f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
