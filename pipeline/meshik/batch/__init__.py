"""Many jobs at once on Dask distributed: each constraint file is one task (Client.submit), results
are taken as they complete (as_completed).

With no scheduler given, the batch starts its own LocalCluster (worker processes on this machine,
one thread each, scheduler and dashboard on 127.0.0.1 only); with a scheduler address or a Client
it runs on that cluster, whose workers must see the input files and the output folder at the same
paths. Each job writes to <out>/<job name>/ through pose_job, so its outputs are complete or
absent, and a job already complete for the same inputs and options is skipped.

Outcomes: "done", "skipped", "failed" (bad input: reported at once with its message, never
retried), "crashed" (its worker died every time it ran it: a crash in the core, the memory limit, a
kill; the scheduler retries a job whose worker died up to `retries` times first), "interrupted"
(Ctrl+C or SIGTERM stopped the batch first). <out>/batch-report.json lists every job.
"""
import json
import logging
import os
import signal
import threading
import time
import uuid
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Sequence, TextIO

from meshik.batch.display import BatchDisplay
from meshik.batch.job import run_job
from meshik.errors import OutputError, PipelineError
from meshik.outputs.safe_paths import child_path
from meshik.outputs.staging import REPORT_NAME, check_not_inputs

SUMMARY_NAME = "batch-report.json"
DEFAULT_RETRIES = 2
DEFAULT_CACHE_MB = 512
SCHEDULER_TIMEOUT = "30s"
_POLL_SECONDS = 0.05
_RUNNING_POLL_SECONDS = 0.5


@dataclass
class JobOutcome:
    """How one job ended: status "done", "skipped", "failed" or "crashed" (with the reason), or
    "interrupted"; worker: "host:pid" of the process that ran it last."""
    name: str
    constraints: str
    out_dir: str
    status: str
    reason: Optional[str] = None
    seconds: float = 0.0
    frames: int = 0
    worker: Optional[str] = None


def job_names(constraint_paths: Sequence[Path]) -> List[str]:
    """Output folder name per constraint file: its stem, prefixed by its folder's name where stems repeat.

    Raises PipelineError when two files still map to one name (e.g. the same file given twice).
    """
    paths = [Path(p) for p in constraint_paths]
    stems = [p.stem for p in paths]
    names = [f"{p.parent.name}-{p.stem}" if stems.count(p.stem) > 1 else p.stem for p in paths]
    for i, name in enumerate(names):
        if names.index(name) != i:
            raise PipelineError(f"{paths[i]} and {paths[names.index(name)]} would both write to the job folder {name!r}")
    return names


@contextmanager
def batch_client(jobs: Optional[int] = None, memory_limit="auto", scheduler: Optional[str] = None,
                 retries: int = DEFAULT_RETRIES) -> Iterator["distributed.Client"]:
    """A Dask Client for a batch, closed (with its cluster) on leaving the block.

    scheduler: address of a running scheduler ("tcp://host:8786"); its own settings then decide the
    retries (distributed.scheduler.allowed-failures); PipelineError when it cannot be reached. Without it: a LocalCluster of `jobs` worker
    processes (default: one per core), one thread each, `memory_limit` per worker ("4GB", "auto":
    the machine's memory shared out, 0: none), a job whose worker died retried up to `retries`
    times, scheduler and dashboard listening on 127.0.0.1 only.
    """
    import dask
    from distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=SCHEDULER_TIMEOUT)
        except (OSError, TimeoutError) as error:
            raise PipelineError(f"cannot reach the Dask scheduler at {scheduler}: {error}") from None
        try:
            yield client
        finally:
            client.close()
        return
    settings = {"distributed.scheduler.allowed-failures": int(retries),
                "distributed.scheduler.worker-saturation": 1.0,  # a worker holds only the job it runs
                # Dask's defaults less MALLOC_TRIM_THRESHOLD_: that setting turns off glibc's adaptive
                # mmap threshold: gallop jobs on one worker took 5-17% longer than in-process with it,
                # 1-11% without (four alternating runs of six shots)
                "distributed.nanny.pre-spawn-environ": {"OMP_NUM_THREADS": 1, "MKL_NUM_THREADS": 1,
                                                        "OPENBLAS_NUM_THREADS": 1}}
    with dask.config.set(settings):
        cluster = LocalCluster(n_workers=jobs or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               memory_limit=memory_limit, host="127.0.0.1", dashboard_address="127.0.0.1:0",
                               silence_logs=logging.ERROR)
    try:
        with Client(cluster) as client:
            yield client
    finally:
        cluster.close()


def run_batch(constraint_paths: Sequence, out_dir, client=None, jobs: Optional[int] = None, memory_limit="auto",
              scheduler: Optional[str] = None, retries: int = DEFAULT_RETRIES, cache_mb: int = DEFAULT_CACHE_MB,
              quiet: bool = False, stream: Optional[TextIO] = None, **job_options: Any) -> List[JobOutcome]:
    """Run pose_job for every constraint file as one Dask task each.

    client: a distributed.Client to run on; without one, batch_client(jobs, memory_limit,
    scheduler, retries) makes one for the batch. cache_mb: each worker's example-set cache bound.
    job_options: JSON-friendly keyword arguments of pose_job (simplify, simplifier, simplify_first, formats,
    feature_space, quantization_bits, force, solver_defaults). Returns one JobOutcome per file, in the order given;
    failures are printed even when quiet. Ctrl+C or SIGTERM stops the batch: no job is left running
    or writing (on a given client, the workers running this batch's jobs are restarted), the
    report lists the unfinished jobs as "interrupted", and KeyboardInterrupt is raised.
    Raises PipelineError when two files would write to the same job folder, OutputError when the
    batch's report or a job's report.json would replace one of the constraint files.
    """
    paths = [Path(p) for p in constraint_paths]
    names = job_names(paths)
    check_not_inputs(Path(out_dir), [SUMMARY_NAME], paths)
    for path, name in zip(paths, names):  # a job's report.json replacing its own constraint file
        check_not_inputs(Path(out_dir) / name, [REPORT_NAME], [path])
    with _sigterm_as_interrupt():
        if client is not None:
            return _run(client, paths, names, Path(out_dir), cache_mb, quiet, stream, job_options, restart_on_stop=True)
        with batch_client(jobs, memory_limit, scheduler, retries) as own:
            return _run(own, paths, names, Path(out_dir), cache_mb, quiet, stream, job_options,
                        restart_on_stop=scheduler is not None)


def _run(client, paths: List[Path], names: List[str], out_dir: Path, cache_mb: int, quiet: bool,
         stream: Optional[TextIO], job_options: Dict[str, Any], restart_on_stop: bool) -> List[JobOutcome]:
    """Submit every job whose name is a safe folder name, collect the outcomes as they complete,
    write the report. restart_on_stop: on an interrupt, restart the workers running our jobs
    (a cluster that outlives the batch); otherwise closing the batch's own cluster stops them."""
    outcomes: List[Optional[JobOutcome]] = [None] * len(paths)
    futures = {}
    with BatchDisplay(len(paths), quiet, stream) as display:
        if "dashboard" in client.scheduler_info().get("services", {}):
            display.note(f"Dask dashboard: {client.dashboard_link}")
        batch_id = uuid.uuid4().hex[:8]
        try:
            for index, (path, name) in enumerate(zip(paths, names)):
                try:
                    folder = child_path(out_dir, name, "job name")
                except OutputError as error:
                    outcomes[index] = JobOutcome(name, str(path), "", "failed", f"{path}: {error}")
                    display.job_finished(name, "failed", outcomes[index].reason, 0.0, 0)
                    continue
                # one task group for all jobs: past twice the cluster's threads the scheduler then queues
                # them (root-ish tasks), so a worker holds only the job it runs and a dying worker takes no other
                future = client.submit(run_job, str(path.absolute()), str(folder.absolute()), job_options,
                                       int(cache_mb) << 20, key=f"meshik-batch-{batch_id}-{index}", pure=False)
                futures[future] = index
            _collect(client, futures, paths, names, out_dir, outcomes, display)
        except KeyboardInterrupt:
            _stop(client, [f for f, i in futures.items() if outcomes[i] is None], restart_on_stop)
            for index, outcome in enumerate(outcomes):
                if outcome is None:
                    outcomes[index] = JobOutcome(names[index], str(paths[index]), str(out_dir / names[index]),
                                                 "interrupted", "the batch was interrupted before this job finished")
            _write_summary(out_dir, outcomes, display)
            raise
    _write_summary(out_dir, outcomes, display)
    return outcomes


def _collect(client, futures: Dict[Any, int], paths: List[Path], names: List[str], out_dir: Path,
             outcomes: List[Optional[JobOutcome]], display: BatchDisplay) -> None:
    """Fill outcomes[i] as each future completes, updating the display (running jobs polled twice a
    second). Results are fetched as soon as each job ends, so that a worker dying afterwards
    (taking the result out of its memory) rarely makes the job run again."""
    from distributed import as_completed

    completed = as_completed(list(futures), with_results=True, raise_errors=False)
    keys = {future.key for future in futures}
    polled = 0.0
    while not completed.is_empty():
        for future, result in completed.next_batch(block=False):
            index = futures[future]
            outcomes[index] = _outcome(future, result, names[index], paths[index], out_dir / names[index])
            o = outcomes[index]
            display.job_finished(o.name, o.status, o.reason, o.seconds, o.frames)
            keys.discard(future.key)  # the future is kept: its task stays in the group the scheduler queues
        if time.monotonic() - polled > _RUNNING_POLL_SECONDS:
            display.set_running(sum(len(keys.intersection(held)) for held in client.processing().values()))
            polled = time.monotonic()
        time.sleep(_POLL_SECONDS)
    display.set_running(0)


def _outcome(future, result, name: str, path: Path, folder: Path) -> JobOutcome:
    """The JobOutcome of a completed future: run_job's result (`result`), or why the task did not
    return one (`result` is then (type, exception, traceback) or the exception)."""
    from distributed import KilledWorker

    if future.status == "finished":
        return JobOutcome(name, str(path), str(folder), result["status"], result["reason"], result["seconds"],
                          result["frames"], result["worker"])
    error = result[1] if isinstance(result, tuple) else result if isinstance(result, BaseException) else None
    if isinstance(error, KilledWorker):
        last = getattr(error.last_worker, "address", error.last_worker)
        runs = error.allowed_failures + 1
        reason = (f"{path}: the worker process died each time it ran this job ({runs} run{'s' if runs > 1 else ''}: "
                  f"a crash, the memory limit or a kill); the last was {last}")
        return JobOutcome(name, str(path), str(folder), "crashed", reason, worker=str(last))
    reason = f"{path}: {type(error).__name__}: {error}" if error is not None else f"{path}: the cluster lost this job ({future.status})"
    return JobOutcome(name, str(path), str(folder), "failed", reason)


def _stop(client, unfinished: List[Any], restart_workers: bool) -> None:
    """Cancel the unfinished jobs; with restart_workers, restart the workers running any of them, so
    that none goes on writing (the nanny starts a fresh process)."""
    keys = {future.key for future in unfinished}
    busy = [worker for worker, held in client.processing().items() if keys.intersection(held)] if restart_workers else []
    client.cancel(unfinished, force=True)
    if busy:
        client.restart_workers(busy, timeout=30, raise_for_error=False)


@contextmanager
def _sigterm_as_interrupt() -> Iterator[None]:
    """Within the block, the first SIGTERM raises KeyboardInterrupt (as Ctrl+C does) and later ones are
    ignored while the batch stops. Only in the main thread (elsewhere signals cannot be handled)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def interrupt(signum, frame):
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGTERM, interrupt)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _write_summary(out_dir: Path, outcomes: List[JobOutcome], display: BatchDisplay) -> None:
    """Write <out>/batch-report.json (atomically) listing every job's outcome; a warning if impossible."""
    temporary = out_dir / f".{SUMMARY_NAME}.{os.getpid()}.tmp"
    counts = {status: sum(o.status == status for o in outcomes)
              for status in ("done", "skipped", "failed", "crashed", "interrupted")}
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        temporary.write_text(json.dumps(dict({"jobs": [asdict(o) for o in outcomes]}, **counts), indent=1))
        os.replace(temporary, out_dir / SUMMARY_NAME)
    except OSError as error:
        display.warn(f"warning: cannot write {out_dir / SUMMARY_NAME}: {error.strerror or error}")
