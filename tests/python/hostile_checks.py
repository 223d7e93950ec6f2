"""The guarantees every hostile case checks (issue 23), shared by the tests/python/test_hostile_*.py files.

A case runs the real `meshik` command line in its own process (its own session, so that whatever
it forks can be found afterwards; in-process where the command cannot die of the case) on a copy of an input folder with one thing broken, and must:
exit with status 1 or 2 (never a signal), print exactly one line on stderr with no traceback,
leave every input file's bytes as they were, write nothing outside --out, finish within its time
limit, and leave no process behind. Cases of one family run a few at a time in parallel.
"""
import hashlib
import os
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional, Sequence

CLI = "import sys; from meshik.cli import main; sys.exit(main())"
PARALLEL = 3


@dataclass
class Outcome:
    """What one run of the command did: exit status, stderr, seconds, and whether its session
    still had processes after it exited (killed then) or it ran past its limit."""
    returncode: int
    stderr: str
    seconds: float
    left_behind: bool
    timed_out: bool


def tree_state(folder: Path) -> Dict[str, str]:
    """{relative path: sha256} of every file under `folder` (links as 'link:<target>')."""
    state = {}
    for path in sorted(folder.rglob("*")):
        relative = str(path.relative_to(folder))
        if path.is_symlink():
            state[relative] = f"link:{os.readlink(path)}"
        elif path.is_file():
            state[relative] = hashlib.sha256(path.read_bytes()).hexdigest()
        elif path.is_dir():
            state[relative] = "folder"
    return state


def run_meshik(args: Sequence, timeout: float = 120, env: Optional[Dict[str, str]] = None) -> Outcome:
    """Run `meshik args...` in a new session (with `env` added to the environment); kill the whole
    session if it runs past `timeout`."""
    start = time.monotonic()
    process = subprocess.Popen([sys.executable, "-c", CLI, *map(str, args)], stdin=subprocess.DEVNULL,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True,
                               env=dict(os.environ, **(env or {})))
    timed_out = False
    try:
        _, stderr = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        os.killpg(process.pid, signal.SIGKILL)
        _, stderr = process.communicate()
    left_behind = session_alive(process.pid)
    if left_behind:
        os.killpg(process.pid, signal.SIGKILL)
    return Outcome(process.returncode, stderr.decode("utf-8", "replace"), time.monotonic() - start, left_behind,
                   timed_out)


def run_in_process(args: Sequence, capsys) -> Outcome:
    """meshik.cli.main(args) in this process (faithful where the command cannot kill its own process:
    the mesh readers run in a forked child); left_behind: whether any child process of this one is
    still alive afterwards (children this process had before the call do not count). capsys: pytest's fixture, whose captured stderr is taken."""
    import psutil

    from meshik.cli import main

    capsys.readouterr()
    earlier = {child.pid for child in psutil.Process().children(recursive=True)}  # other tests' (a Dask nanny ending)
    start = time.monotonic()
    code = main([str(a) for a in args])
    seconds = time.monotonic() - start
    children = [child for child in psutil.Process().children(recursive=True) if child.pid not in earlier]
    _, still = psutil.wait_procs(children, timeout=1.0)
    return Outcome(code, capsys.readouterr().err, seconds, bool(still), False)


def run_forked(args: Sequence, timeout: float = 60) -> Outcome:
    """meshik.cli.main(args) in a forked copy of this process, in its own session: as isolated as a
    new process (a signal death shows as a negative returncode) without paying for the imports."""
    read_end, write_end = os.pipe()
    start = time.monotonic()
    pid = os.fork()
    if pid == 0:  # the child: stderr into the pipe, run, leave without the parent's clean-up
        code = 99
        try:
            os.setsid()
            os.close(read_end)
            null = os.open(os.devnull, os.O_RDWR)
            os.dup2(null, 0)
            os.dup2(null, 1)
            os.dup2(write_end, 2)
            sys.stdout = open(1, "w", closefd=False)  # not pytest's capture objects
            sys.stderr = open(2, "w", closefd=False)
            from meshik.cli import main

            code = main([str(a) for a in args])
        except BaseException:  # noqa: BLE001 - shown as a traceback, which the checks refuse
            import traceback

            traceback.print_exc()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
    os.close(write_end)
    chunks, timed_out = [], False
    with os.fdopen(read_end, "rb") as stream:
        os.set_blocking(read_end, False)
        while True:
            try:
                chunk = stream.read()
            except BlockingIOError:
                chunk = None
            if chunk:
                chunks.append(chunk)
            elif chunk == b"":
                break
            if time.monotonic() - start > timeout:
                timed_out = True
                os.killpg(pid, signal.SIGKILL)
                break
            time.sleep(0.01)
    _, status = os.waitpid(pid, 0)
    code = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
    left_behind = session_alive(pid)
    if left_behind:
        os.killpg(pid, signal.SIGKILL)
    return Outcome(code, b"".join(chunks).decode("utf-8", "replace"), time.monotonic() - start, left_behind, timed_out)


def session_alive(session: int, grace: float = 5.0) -> bool:
    """Whether any process of process group `session` still runs `grace` seconds after the command
    exited (a Dask worker may take a second or two to finish exiting after its batch)."""
    for _ in range(int(grace / 0.05)):
        try:
            os.killpg(session, 0)
        except ProcessLookupError:
            return False
        time.sleep(0.05)
    return True


def run_all(cases: Dict[str, Sequence], timeout: float = 120, env: Optional[Dict[str, str]] = None) -> Dict[str, Outcome]:
    """run_meshik for every case's arguments, PARALLEL at a time; {case: Outcome}."""
    with ThreadPoolExecutor(PARALLEL) as pool:
        futures = {name: pool.submit(run_meshik, args, timeout, env) for name, args in cases.items()}
        return {name: future.result() for name, future in futures.items()}


def assert_refused(outcome: Outcome, expected: str = "", inputs: Optional[Path] = None,
                   before: Optional[Dict[str, str]] = None, work: Optional[Path] = None,
                   allowed: Sequence[str] = ("in", "out")) -> None:
    """The guarantees above; expected: text the error line must contain. inputs/before: the input
    folder and its tree_state before the run; work: the folder holding inputs and --out, in which
    only `allowed` names may exist (nothing written beside --out)."""
    lines = [line for line in outcome.stderr.splitlines() if line.strip()]
    assert not outcome.timed_out, f"ran past its limit: {outcome.stderr}"
    assert outcome.returncode in (1, 2), f"exit {outcome.returncode}: {outcome.stderr}"
    assert "Traceback" not in outcome.stderr, outcome.stderr
    assert len(lines) == 1, f"{len(lines)} lines on stderr: {outcome.stderr!r}"
    assert "\x1b" not in outcome.stderr, "a raw escape sequence reached the terminal"
    assert expected in lines[0], f"{expected!r} not in {lines[0]!r}"
    assert not outcome.left_behind, "a process of the run was still alive after it exited"
    if inputs is not None and before is not None:
        assert tree_state(inputs) == before, "an input changed"
    if work is not None:
        extra = sorted(set(p.name for p in work.iterdir()) - set(allowed))
        assert not extra, f"written outside --out: {extra}"


def names_in(folder: Path) -> List[str]:
    """Sorted names in `folder` ([] when it does not exist)."""
    return sorted(p.name for p in folder.iterdir()) if folder.is_dir() else []
