"""Progress display on stderr with `rich`: one bar per stage of a job, and the console the batch
display and its messages share.

On a terminal the bar redraws in place; elsewhere (logs, pipes) only the finished line is printed.
"""
from contextlib import contextmanager
from typing import Callable, Iterator, Optional, TextIO

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TaskProgressColumn, TextColumn, TimeElapsedColumn

from meshik.terminal_text import one_line

_LOG_WIDTH = 160


def console_for(stream: Optional[TextIO]) -> Console:
    """A rich Console writing to `stream` (default: sys.stderr as it is at each write), no markup
    or highlighting of the text it prints, lines never wrapped; 160 columns wide when the stream is
    not a terminal (logs), so that a bar's line is not cut."""
    console = Console(stderr=True, highlight=False, soft_wrap=True) if stream is None else \
        Console(file=stream, highlight=False, soft_wrap=True)
    if not console.is_terminal:
        console.width = _LOG_WIDTH
    return console


def say(console: Console, line: str) -> None:
    """Print one plain line (no markup interpretation, control characters escaped: one_line) above
    any live display."""
    console.print(one_line(line), markup=False)


@contextmanager
def stage_progress(label: str, total: int, quiet: bool = False, stream: Optional[TextIO] = None) -> Iterator[Callable[[], None]]:
    """A bar "label  12/48 ━━━━━━━   25% 0:00:01" for a stage of `total` steps; yields advance(),
    to be called once per step. quiet: no display at all. The label is shown as plain text, control
    characters escaped (one_line)."""
    progress = Progress(TextColumn("{task.description}", markup=False), BarColumn(bar_width=24), MofNCompleteColumn(),
                        TaskProgressColumn(), TimeElapsedColumn(), console=console_for(stream), disable=quiet)
    task = progress.add_task(one_line(label), total=max(int(total), 1))
    with progress:
        yield lambda: progress.advance(task)
        progress.update(task, completed=max(int(total), 1))
