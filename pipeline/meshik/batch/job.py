"""One batch job as a Dask task: the function the workers run (importable on every worker).

run_job never raises for a failing job: bad input comes back as status "failed" with its message,
so Dask does not retry it. Only the death of the worker process (a crash in the core, the memory
limit, a kill) makes the scheduler run the job again on another worker.
"""
import ctypes
import gc
import os
import signal
import socket
import time
from pathlib import Path
from typing import Any, Dict, Optional

from meshik.posing.example_cache import ExampleSetCache

# Test-only fault: "JOB,TIMES,MARKER" makes job JOB SIGKILL its own worker process half a second
# into its run,
# TIMES times in all (the file MARKER records the ids of the processes killed); several such
# specifications are separated by ";".
KILL_WORKER_VARIABLE = "MESHIK_TEST_KILL_WORKER"

_KILL_AFTER_SECONDS = 0.5
# A worker's cache is trimmed after a job while its resident memory is above this fraction of
# Dask's pause threshold.
PAUSE_MARGIN = 0.85

_cache: Optional[ExampleSetCache] = None


def run_job(constraints: str, destination: str, options: Dict[str, Any], cache_bytes: int) -> Dict[str, Any]:
    """Pose one constraint file into `destination` with meshik.pipeline.pose_job.

    options: pose_job keyword arguments (simplify, simplifier, simplify_first, formats, feature_space,
    quantization_bits, force, solver_defaults); cache_bytes: memory bound of this process's example-set cache
    (0: no cache). Returns {"status": "done" | "skipped" | "failed", "reason": message or None,
    "frames": frame count, "seconds": time in this function, "worker": "host:pid"}.
    """
    from meshik.pipeline import pose_job

    start = time.perf_counter()
    _maybe_kill_worker(Path(destination).name)
    try:
        report = pose_job(constraints, destination, quiet=True, example_cache=example_cache(cache_bytes),
                          within=Path(destination).parent, **options)
        status, reason, frames = ("skipped" if report.get("skipped") else "done"), None, report.get("frame_count", 0)
    except ValueError as error:  # PipelineError and the core's InputError: bad input, the message says why
        status, reason, frames = "failed", str(error), 0
    except Exception as error:  # noqa: BLE001 - any other failure is reported with its type, never retried
        status, reason, frames = "failed", f"{type(error).__name__}: {error}", 0
    _stay_below_pause(example_cache(cache_bytes))
    return {"status": status, "reason": reason, "frames": frames, "seconds": time.perf_counter() - start,
            "worker": f"{socket.gethostname()}:{os.getpid()}"}


def _stay_below_pause(cache: Optional[ExampleSetCache]) -> None:
    """Drop cached example sets while this Dask worker's resident memory is above PAUSE_MARGIN of
    the level where Dask pauses it (memory limit x pause fraction): a paused worker takes no job,
    so a cache holding it there would stall the batch for ever. Freed heap is handed back to the
    system (malloc_trim) so that the resident size Dask watches falls. Nothing outside a worker
    with a memory limit."""
    if cache is None:
        return
    try:
        from distributed import get_worker

        manager = get_worker().memory_manager
    except (ImportError, ValueError, AttributeError):  # not in a Dask worker
        return
    limit, pause = manager.memory_limit, manager.memory_pause_fraction
    if not limit or not pause:
        return
    import psutil

    excess = psutil.Process().memory_info().rss - int(PAUSE_MARGIN * pause * limit)
    if excess > 0 and cache.release(excess):
        gc.collect()
        try:
            ctypes.CDLL("libc.so.6").malloc_trim(0)
        except (OSError, AttributeError):  # not glibc
            pass


def example_cache(max_bytes: int) -> Optional[ExampleSetCache]:
    """This process's example-set cache, created on first use and bounded to max_bytes; None for 0."""
    global _cache
    if max_bytes <= 0:
        return None
    if _cache is None:
        _cache = ExampleSetCache(max_bytes)
    _cache.max_bytes = max_bytes
    return _cache


def _maybe_kill_worker(job: str) -> None:
    """The test-only fault of KILL_WORKER_VARIABLE: SIGKILL this process when it names this job and
    has not yet killed as many times as it says."""
    for spec in filter(None, os.environ.get(KILL_WORKER_VARIABLE, "").split(";")):
        name, times, marker = spec.split(",", 2)
        marker_path = Path(marker)
        killed = marker_path.read_text().split() if marker_path.exists() else []
        if name == job and len(killed) < int(times):
            marker_path.write_text(" ".join(killed + [str(os.getpid())]))
            time.sleep(_KILL_AFTER_SECONDS)  # long after the previous job's result left this worker
            os.kill(os.getpid(), signal.SIGKILL)
