"""Many jobs at once: each constraint file is posed in its own worker process.

A job that fails (bad input, or even a crashed process) is reported with its reason and does
not stop the others. Each job writes to <out>/<job name>/ through pose_job, so its outputs are
complete or absent, and a job already complete for the same inputs and options is skipped.
A summary of all jobs is written to <out>/batch-report.json.
"""
import json
import multiprocessing
import os
import time
from dataclasses import asdict, dataclass
from multiprocessing.connection import wait
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, TextIO

from meshik.errors import PipelineError
from meshik.progress import Progress

SUMMARY_NAME = "batch-report.json"


@dataclass
class JobOutcome:
    """How one job ended: status "done", "skipped" (already complete) or "failed" (with reason)."""
    name: str
    constraints: str
    out_dir: str
    status: str
    reason: Optional[str] = None
    seconds: float = 0.0
    frames: int = 0


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


def run_batch(constraint_paths: Sequence, out_dir, jobs: int = 1, quiet: bool = False, stream: Optional[TextIO] = None,
              **job_options: Any) -> List[JobOutcome]:
    """Run pose_job for every constraint file with up to `jobs` worker processes at a time.

    job_options: keyword arguments of pose_job (simplify, simplifier, formats, feature_space,
    quantization_bits, force). Returns one JobOutcome per file, in the order given; failures are
    printed even when quiet.
    """
    import sys

    stream = stream or sys.stderr
    paths = [Path(p) for p in constraint_paths]
    out_dir = Path(out_dir)
    names = job_names(paths)
    context = multiprocessing.get_context("spawn")
    progress = Progress("batch", len(paths), quiet=quiet, stream=stream)
    outcomes: List[Optional[JobOutcome]] = [None] * len(paths)
    waiting = list(range(len(paths)))
    running: Dict[int, Any] = {}
    try:
        while waiting or running:
            while waiting and len(running) < max(1, jobs):
                index = waiting.pop(0)
                receiver, sender = context.Pipe(duplex=False)
                process = context.Process(target=_worker, args=(str(paths[index]), str(out_dir / names[index]), job_options, sender),
                                          name=f"meshik-{names[index]}", daemon=True)
                process.start()
                sender.close()
                running[index] = (process, receiver, time.perf_counter())
            ready = wait([r for _, r, _ in running.values()] + [p.sentinel for p, _, _ in running.values()])
            for index, (process, receiver, started) in list(running.items()):
                if receiver not in ready and process.sentinel not in ready:
                    continue
                outcome = _collect(receiver, process, names[index], paths[index], out_dir / names[index], started)
                outcomes[index] = outcome
                del running[index]
                _announce(outcome, quiet, stream, clear_line=progress.interactive)
                progress.advance()
    except KeyboardInterrupt:
        for process, _, _ in running.values():
            process.terminate()
        raise
    progress.finish()
    _write_summary(out_dir, outcomes, stream)
    return outcomes


def _worker(constraints: str, destination: str, job_options: Dict[str, Any], sender) -> None:
    """Worker process body: run one job, send (status, reason, frames) back through the pipe."""
    from meshik.pipeline import pose_job

    try:
        report = pose_job(constraints, destination, quiet=True, **job_options)
        sender.send(("skipped" if report.get("skipped") else "done", None, report.get("frame_count", 0)))
    except ValueError as error:  # PipelineError and the core's InputError: bad input, message says why
        sender.send(("failed", str(error), 0))
    except Exception as error:  # noqa: BLE001 - any other failure is reported with its type, not raised
        sender.send(("failed", f"{type(error).__name__}: {error}", 0))
    finally:
        sender.close()


def _collect(receiver, process, name: str, constraints: Path, destination: Path, started: float) -> JobOutcome:
    """The outcome of a finished worker: its message, or "worker process died" when it sent none."""
    message = None
    if receiver.poll():
        try:
            message = receiver.recv()
        except EOFError:
            message = None
    process.join()
    receiver.close()
    seconds = time.perf_counter() - started
    if message is None:
        code = process.exitcode
        how = f"was killed by signal {-code}" if code is not None and code < 0 else f"exited with status {code}"
        return JobOutcome(name, str(constraints), str(destination), "failed", f"worker process {how} without a result", seconds)
    status, reason, frames = message
    return JobOutcome(name, str(constraints), str(destination), status, reason, seconds, frames)


def _announce(outcome: JobOutcome, quiet: bool, stream: TextIO, clear_line: bool) -> None:
    """One line per finished job (failures always, the others unless quiet); clear_line: erase the
    progress line drawn in place on a terminal first."""
    prefix = "\r\033[K" if clear_line else ""
    if outcome.status == "failed":
        stream.write(f"{prefix}{outcome.name}: FAILED: {outcome.reason}\n")
    elif not quiet:
        what = "skipped (outputs already complete)" if outcome.status == "skipped" else f"done, {outcome.frames} frames"
        stream.write(f"{prefix}{outcome.name}: {what} in {outcome.seconds:.1f} s\n")
    stream.flush()


def _write_summary(out_dir: Path, outcomes: List[JobOutcome], stream: TextIO) -> None:
    """Write <out>/batch-report.json (atomically) listing every job's outcome; a warning if impossible."""
    temporary = out_dir / f".{SUMMARY_NAME}.{os.getpid()}.tmp"
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        temporary.write_text(json.dumps({"jobs": [asdict(o) for o in outcomes],
                                         "failed": sum(o.status == "failed" for o in outcomes)}, indent=1))
        os.replace(temporary, out_dir / SUMMARY_NAME)
    except OSError as error:
        stream.write(f"warning: cannot write {out_dir / SUMMARY_NAME}: {error.strerror or error}\n")
