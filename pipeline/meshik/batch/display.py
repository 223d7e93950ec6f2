"""The live display of a batch on stderr (rich): jobs done / failed / crashed / running, frames per
second, ETA, and one line per finished job above it.

On a terminal the bar redraws in place; elsewhere only the job lines and the final bar are printed.
Failures are always printed; quiet hides everything else.
"""
import time
from typing import Optional, TextIO

from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

from meshik.progress_bars import console_for, say


class BatchDisplay:
    """Counts of a batch's jobs and their live bar; use as a context manager around the batch."""

    def __init__(self, total: int, quiet: bool = False, stream: Optional[TextIO] = None):
        """total: number of jobs; quiet: only failures are printed."""
        self.quiet = quiet
        self.console = console_for(stream)
        self.counts = {"done": 0, "skipped": 0, "failed": 0, "crashed": 0}
        self.running = 0
        self.frames = 0
        self.started = time.perf_counter()
        self._progress = Progress(TextColumn("batch"), BarColumn(bar_width=24), MofNCompleteColumn(),
                                  TextColumn("{task.fields[summary]}"), TimeRemainingColumn(),
                                  console=self.console, disable=quiet)
        self._task = self._progress.add_task("batch", total=max(total, 1), summary=self._summary())

    def note(self, line: str) -> None:
        """A line of information (e.g. the dashboard's address); hidden when quiet."""
        if not self.quiet:
            say(self.console, line)

    def warn(self, line: str) -> None:
        """A warning line, printed even when quiet."""
        say(self.console, line)

    def job_finished(self, name: str, status: str, reason: Optional[str], seconds: float, frames: int) -> None:
        """Count a finished job and print its line (failed and crashed jobs even when quiet)."""
        self.counts[status] = self.counts.get(status, 0) + 1
        self.frames += frames if status == "done" else 0
        if status in ("failed", "crashed"):
            say(self.console, f"{name}: {status.upper()}: {reason}")
        elif not self.quiet:
            what = "skipped (outputs already complete)" if status == "skipped" else f"done, {frames} frames"
            say(self.console, f"{name}: {what} in {seconds:.1f} s")
        self._progress.update(self._task, advance=1, summary=self._summary())

    def set_running(self, running: int) -> None:
        """Number of jobs the workers are running now."""
        self.running = running
        self._progress.update(self._task, summary=self._summary())

    def _summary(self) -> str:
        """"3 done, 1 failed, 2 running, 41.0 frames/s" (statuses other than done only when they occur)."""
        rate = self.frames / max(time.perf_counter() - self.started, 1e-9)
        counts = ", ".join(f"{n} {status}" for status, n in self.counts.items() if n or status == "done")
        return f"{counts}, {self.running} running, {rate:.1f} frames/s"

    def __enter__(self) -> "BatchDisplay":
        self._progress.start()
        return self

    def __exit__(self, *exc_info) -> None:
        self._progress.stop()
