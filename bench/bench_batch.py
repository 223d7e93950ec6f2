"""Batch benchmark (run by `make bench` with --samples DIR --data DIR).

24 shots of the horse gallop (48 frames each, the frames rotated so that every shot differs, all
posing horse-poses: one shared example set), run
  - plain: pose_job one after the other in this process (no Dask), without and with the
    example-set cache (the cache's gain);
  - on Dask: a LocalCluster and a loopback cluster (`python -m dask scheduler` / `worker`
    processes on 127.0.0.1), each with 1 and 2 workers, through meshik.batch.run_batch.
Each cluster is started and its workers import the pipeline before the clock starts.
Reported: shots per minute; Dask's overhead per job, (wall x workers - time inside the jobs) / jobs,
and for one worker also (wall - plain wall) / jobs, against a plain run made just before it (the
machine is shared: load drifts); both as a share of a gallop-sized job.
"""
import argparse
import json
import pathlib
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "python"))  # the loopback cluster of the tests

SHOTS = 24
HANDLES = 12


def main() -> int:
    """Print the table; exit status 0 (the numbers are for reading, not a pass/fail floor)."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=pathlib.Path, help="sample_meshes/ (unused here)")
    parser.add_argument("--data", type=pathlib.Path, required=True, help="../shared/data")
    parser.add_argument("--shots", type=int, default=SHOTS, help=f"number of shots (default {SHOTS})")
    args = parser.parse_args()
    horse, gallop = args.data / "horse-poses", args.data / "horse-gallop"
    if not (horse.is_dir() and gallop.is_dir()):
        print(f"bench_batch: skipped, {horse} or {gallop} not found")
        return 0
    with tempfile.TemporaryDirectory(prefix="meshik-bench-batch-") as scratch:
        scratch = pathlib.Path(scratch)
        shots = write_shots(horse, gallop, scratch / "shots", args.shots)
        run_all(shots, scratch)
    return 0


def write_shots(horse: pathlib.Path, gallop: pathlib.Path, folder: pathlib.Path, count: int):
    """`count` constraint files following the gallop (12 tracked vertices), shot k starting at frame k."""
    from bench_pipeline import horse_files
    from meshik.inputs.meshio import load_mesh
    from meshik.inputs.tracking import farthest_point_handles, tracking_document

    folder.mkdir(parents=True)
    rest_path, examples = horse_files(horse)
    rest, _ = load_mesh(rest_path)
    frames = [(p.stem, load_mesh(p)[0]) for p in sorted(gallop.glob("*.obj")) if p.stem.isdigit()]
    handles = farthest_point_handles(rest, HANDLES)
    paths = []
    for k in range(count):
        rotated = dict(frames[k % len(frames):] + frames[:k % len(frames)])
        path = folder / f"shot{k:02d}.json"
        path.write_text(json.dumps(tracking_document(path, rest_path, examples, rotated, handles)))
        paths.append(path)
    return paths


def run_all(shots, scratch: pathlib.Path) -> None:
    """Every configuration in turn, then the table."""
    from meshik.batch import DEFAULT_CACHE_MB

    rows, plain_before = [], {}  # plain_before: a plain run made just before each one-worker Dask run
    plain_uncached = run_plain(shots, scratch / "plain-uncached", cache_mb=0)
    rows.append(("plain, no cache", 1, plain_uncached))
    plain = run_plain(shots, scratch / "plain", cache_mb=DEFAULT_CACHE_MB)
    rows.append(("plain, cache", 1, plain))
    for workers in (1, 2):
        for name, run in (("Dask LocalCluster", run_local), ("Dask loopback cluster", run_loopback)):
            if workers == 1:
                plain_before[name] = run_plain(shots, scratch / f"plain-{len(plain_before)}", DEFAULT_CACHE_MB)[0]
            rows.append((name, workers, run(shots, scratch / f"{run.__name__}{workers}", workers)))
    frames = sum(json.loads(s.read_text())["frames"].__len__() for s in shots)
    job = plain[0] / len(shots)  # a gallop-sized job, plain, with the cache
    print(f"{len(shots)} shots of the horse gallop ({frames // len(shots)} frames, {HANDLES} handle vertices, "
          f"8,431 vertices, 10 examples), drc + glb")
    print(f"example-set cache: plain run {plain_uncached[0]:.2f} s without, {plain[0]:.2f} s with: "
          f"{plain_uncached[0] / plain[0]:.2f}x ({(plain_uncached[0] - plain[0]) / len(shots) * 1e3:.0f} ms saved per job)")
    print(f"gallop-sized job, plain with the cache: {job * 1e3:.0f} ms")
    print(f"{'run':<24}{'workers':>8}{'wall s':>9}{'shots/min':>11}{'overhead/job ms':>17}{'of a job':>10}"
          f"{'vs plain ms/job':>17}{'of a job':>10}")
    for name, workers, (wall, inside) in rows:
        overhead = (wall * workers - inside) / len(shots)
        line = (f"{name:<24}{workers:>8}{wall:>9.2f}{60 * len(shots) / wall:>11.1f}{overhead * 1e3:>17.1f}"
                f"{100 * overhead / job:>9.1f}%")
        if workers == 1 and name in plain_before:
            versus = (wall - plain_before[name]) / len(shots)
            line += f"{versus * 1e3:>17.1f}{100 * versus / job:>9.1f}%"
        print(line)


def run_plain(shots, out: pathlib.Path, cache_mb: int):
    """(wall seconds, seconds inside the jobs) of run_job called in this process for every shot."""
    from meshik.batch import job as batch_job

    batch_job._cache = None  # a fresh cache, as a fresh worker has
    start = time.perf_counter()
    inside = sum(batch_job.run_job(str(s), str(out / s.stem), {"formats": ["drc", "glb"]}, cache_mb << 20)["seconds"]
                 for s in shots)
    return time.perf_counter() - start, inside


def run_on(client, shots, out: pathlib.Path, workers: int):
    """(wall seconds, seconds inside the jobs) of run_batch on a started client, its workers warmed
    up first (the pipeline imported in each)."""
    from meshik.batch import run_batch

    client.wait_for_workers(workers)
    client.run(_import_pipeline)
    start = time.perf_counter()
    outcomes = run_batch(shots, out / "shots", client=client, quiet=True, formats=("drc", "glb"))
    wall = time.perf_counter() - start
    assert all(o.status == "done" for o in outcomes), [o.reason for o in outcomes if o.status != "done"]
    return wall, sum(o.seconds for o in outcomes)


def run_local(shots, out: pathlib.Path, workers: int):
    """run_on a LocalCluster of `workers` processes."""
    from meshik.batch import batch_client

    with batch_client(jobs=workers) as client:
        return run_on(client, shots, out, workers)


def run_loopback(shots, out: pathlib.Path, workers: int):
    """run_on a scheduler and `workers` worker processes started as in the tests."""
    from dask_processes import LoopbackCluster
    from distributed import Client

    with LoopbackCluster(out / "cluster", workers=workers,
                         scheduler_env={"DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION": "1.0"}) as cluster:
        with Client(cluster.address) as client:
            return run_on(client, shots, out, workers)


def _import_pipeline() -> None:
    """Run on each worker before the clock starts: the imports a first job would otherwise pay for."""
    import meshik.pipeline  # noqa: F401


if __name__ == "__main__":
    sys.exit(main())
