"""Progress display on stderr with `rich`: one bar per stage of a job, and the console the batch
display and its messages share.

On a terminal the bar redraws in place; elsewhere (logs, pipes) only the finished line is printed.
"""
from contextlib import contextmanager
from typing import Callable, Iterator, Optional, TextIO

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TaskProgressColumn, TextColumn, TimeElapsedColumn

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
    """Print one plain line (no markup interpretation) above any live display."""
    console.print(line, markup=False)


@contextmanager
def stage_progress(label: str, total: int, quiet: bool = False, stream: Optional[TextIO] = None) -> Iterator[Callable[[], None]]:
    """A bar "label  12/48 ━━━━━━━   25% 0:00:01" for a stage of `total` steps; yields advance(),
    to be called once per step. quiet: no display at all."""
    progress = Progress(TextColumn("{task.description}"), BarColumn(bar_width=24), MofNCompleteColumn(),
                        TaskProgressColumn(), TimeElapsedColumn(), console=console_for(stream), disable=quiet)
    task = progress.add_task(label, total=max(int(total), 1))
    with progress:
        yield lambda: progress.advance(task)
        progress.update(task, completed=max(int(total), 1))
