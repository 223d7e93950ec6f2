"""Many jobs at once: each constraint file is posed in its own worker process.

A job that fails (bad input, or even a crashed process) is reported with its reason and does
not stop the others. Workers are plain `python -m meshik.batch_worker` processes (not
multiprocessing), so they work whatever script started the batch. Each job writes to
<out>/<job name>/ through pose_job, so its outputs are complete or absent, and a job already
complete for the same inputs and options is skipped. <out>/batch-report.json lists every job.
"""
import json
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, TextIO

from meshik.errors import PipelineError
from meshik.progress import Progress

SUMMARY_NAME = "batch-report.json"
_POLL_SECONDS = 0.05


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

    job_options: JSON-friendly keyword arguments of pose_job (simplify, simplifier, formats,
    feature_space, quantization_bits, force). Returns one JobOutcome per file, in the order given;
    failures are printed even when quiet.
    """
    stream = stream or sys.stderr
    paths = [Path(p) for p in constraint_paths]
    out_dir = Path(out_dir)
    names = job_names(paths)
    progress = Progress("batch", len(paths), quiet=quiet, stream=stream)
    outcomes: List[Optional[JobOutcome]] = [None] * len(paths)
    waiting = list(range(len(paths)))
    running: Dict[int, _Worker] = {}
    try:
        while waiting or running:
            while waiting and len(running) < max(1, jobs):
                index = waiting.pop(0)
                running[index] = _Worker(paths[index], out_dir / names[index], job_options)
            time.sleep(_POLL_SECONDS)
            for index, worker in list(running.items()):
                if worker.process.poll() is None:
                    continue
                outcomes[index] = worker.outcome(names[index])
                del running[index]
                _announce(outcomes[index], quiet, stream, clear_line=progress.interactive)
                progress.advance()
    except KeyboardInterrupt:
        for worker in running.values():
            worker.stop()
        raise
    progress.finish()
    _write_summary(out_dir, outcomes, stream)
    return outcomes


class _Worker:
    """One job running in its own Python process; its result comes back as JSON in a temporary file."""

    def __init__(self, constraints: Path, destination: Path, job_options: Dict[str, Any]):
        """Start `python -m meshik.batch_worker` for one job (stderr kept in a temporary file)."""
        self.constraints, self.destination = constraints, destination
        self.started = time.perf_counter()
        self.folder = tempfile.TemporaryDirectory(prefix="meshik-job-")
        self.result = Path(self.folder.name) / "result.json"
        self.log = open(Path(self.folder.name) / "stderr.txt", "w+b")
        spec = {"constraints": str(constraints), "destination": str(destination), "options": job_options,
                "result": str(self.result)}
        package_root = str(Path(__file__).resolve().parent.parent)
        search_path = os.pathsep.join(filter(None, [package_root, os.environ.get("PYTHONPATH")]))
        self.process = subprocess.Popen([sys.executable, "-m", "meshik.batch_worker", json.dumps(spec)],
                                        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=self.log,
                                        env=dict(os.environ, PYTHONPATH=search_path))

    def outcome(self, name: str) -> JobOutcome:
        """The finished job's outcome: its result file, or why the process ended without one."""
        seconds = time.perf_counter() - self.started
        try:
            status, reason, frames = json.loads(self.result.read_text())
        except (OSError, ValueError):
            code = self.process.returncode
            how = f"was killed by signal {-code}" if code < 0 else f"exited with status {code}"
            self.log.seek(0)
            last = [line for line in self.log.read().decode(errors="replace").splitlines() if line.strip()][-1:]
            status, reason, frames = "failed", f"worker process {how} without a result" + (f": {last[0]}" if last else ""), 0
        finally:
            self.log.close()
            self.folder.cleanup()
        return JobOutcome(name, str(self.constraints), str(self.destination), status, reason, seconds, frames)

    def stop(self) -> None:
        """Interrupt the worker (it discards its staged outputs) and wait for it."""
        self.process.terminate()
        self.process.wait()
        self.log.close()
        self.folder.cleanup()


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
