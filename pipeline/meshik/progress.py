"""A one-line progress display on stderr (no dependency): "label  12/48 [#####.....]  25%".

On a terminal the line redraws in place (at most 10 times a second); elsewhere (logs, pipes)
only the finished line is printed. A quiet Progress prints nothing.
"""
import sys
import time
from typing import Optional, TextIO

_WIDTH = 24
_REDRAW_SECONDS = 0.1


class Progress:
    """Progress of one stage of work with a known number of steps."""

    def __init__(self, label: str, total: int, quiet: bool = False, stream: Optional[TextIO] = None):
        """label: what is being done; total: number of steps; quiet: print nothing."""
        self.label = label
        self.total = max(int(total), 1)
        self.done = 0
        self.quiet = quiet
        self.stream = stream if stream is not None else sys.stderr
        self.interactive = bool(getattr(self.stream, "isatty", lambda: False)())
        self._last_draw = 0.0

    def advance(self, steps: int = 1) -> None:
        """Count `steps` more steps as done and redraw when due."""
        self.done = min(self.done + steps, self.total)
        now = time.monotonic()
        if self.interactive and not self.quiet and (now - self._last_draw >= _REDRAW_SECONDS or self.done == self.total):
            self._draw(end="")
            self._last_draw = now

    def finish(self, note: str = "") -> None:
        """Mark the stage complete and end its line (with an optional note, e.g. a time)."""
        self.done = self.total
        if not self.quiet:
            self._draw(end="\n", note=note)

    def _draw(self, end: str, note: str = "") -> None:
        """Write the line: label, count, bar, percentage, note."""
        filled = int(_WIDTH * self.done / self.total)
        bar = "#" * filled + "." * (_WIDTH - filled)
        prefix = "\r" if self.interactive else ""
        text = f"{prefix}{self.label}  {self.done}/{self.total} [{bar}] {100 * self.done // self.total:3d}%"
        self.stream.write(text + (f"  {note}" if note else "") + end)
        self.stream.flush()
