"""Reading mesh files without trusting the reader: checks first, then MeshLab's reader in a child.

Some of MeshLab's readers crash the process on malformed files (an OBJ or OFF face index out of
range is a segmentation fault inside the reader). A crash must not take the CLI, a batch worker or
a notebook down with it, nor be reported as "killed by signal 11": the reader runs in a forked
child process that sends the arrays back through a pipe, and a child that dies is reported as a
malformed file, naming it. Others never finish on some malformed files (an STL of zero bytes loops
forever): the child has a time limit (READ_SECONDS_BASE plus READ_SECONDS_PER_MB of the file) and is
killed past it. The child dies with its parent whatever the parent's exit (PR_SET_PDEATHSIG, and a
kill on any exception in the parent, Ctrl+C included), takes SIGINT and SIGTERM by their default
action, and writes nothing on the caller's stdout or stderr (a reader's or glibc's message about a
malformed file would be a second line beside the one error the caller prints).
"""
import ctypes
import faulthandler
import io
import os
import select
import signal
import stat
import time
from pathlib import Path
from typing import Optional, Tuple

import numpy as np

from meshik.errors import MeshFileError
from meshik.inputs.meshlab_module import pymeshlab_module
from meshik.outputs.safe_paths import utf8_name

# Mesh files larger than this are refused before reading (a bound on memory, and /dev/zero).
MAX_INPUT_BYTES = 4 << 30
# The reader child's time limit: READ_SECONDS_BASE (or the environment's READ_SECONDS_VARIABLE, a
# positive number) plus READ_SECONDS_PER_MB per MB of the file (MeshLab reads about 20 MB/s of OBJ
# text on one core of this machine; the limit is 60 times that). Seen: an empty .vmi never finishes.
READ_SECONDS_BASE = 30.0
READ_SECONDS_PER_MB = 3.0
READ_SECONDS_VARIABLE = "MESHIK_READER_SECONDS"
_PR_SET_PDEATHSIG = 1


def check_input_file(path: Path, what: str) -> None:
    """MeshFileError unless `path` is an existing regular file no larger than MAX_INPUT_BYTES.

    Says which: missing, a folder, a device or FIFO (never read: it could block or never end),
    or too large.
    """
    utf8_name(path, MeshFileError)
    try:
        status = path.stat()
    except FileNotFoundError:
        raise MeshFileError(f"{path}: {what} not found") from None
    except OSError as error:
        raise MeshFileError(f"{path}: cannot read the {what}: {error.strerror or error}") from None
    if stat.S_ISDIR(status.st_mode):
        raise MeshFileError(f"{path}: is a folder, not a {what}")
    if not stat.S_ISREG(status.st_mode):
        raise MeshFileError(f"{path}: is not a regular file (a device, FIFO or socket), not a {what}")
    if status.st_size > MAX_INPUT_BYTES:
        raise MeshFileError(f"{path}: {status.st_size} bytes is larger than the {MAX_INPUT_BYTES >> 30} GiB "
                            f"accepted for a {what}")
    if not os.access(path, os.R_OK):
        raise MeshFileError(f"{path}: cannot read the {what}: permission denied")


def isolated_load(path: Path, time_limit: Optional[float] = None) -> Tuple[np.ndarray, np.ndarray]:
    """(#V by 3 float64 positions, #F by 3 int64 triangles) read by pymeshlab in a forked child.

    time_limit: seconds the child may take (None: read_time_limit of the file's size).
    Raises MeshFileError naming `path` when the reader refuses the file, dies on it or does not
    finish within the limit (the child is then killed).
    """
    pymeshlab = pymeshlab_module()  # imported before the fork, so the child does not import it again
    limit = read_time_limit(path) if time_limit is None else time_limit
    parent = os.getpid()
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: read, send, and leave without running the parent's clean-up
        os.close(read_end)
        _become_reader_child(parent)
        status = 0
        try:
            _send(write_end, _read_with_pymeshlab(pymeshlab, path))
        except BaseException:
            status = 3
        os._exit(status)
    os.close(write_end)
    try:
        payload = _read_until(read_end, time.monotonic() + limit)
    except BaseException:  # Ctrl+C, SIGTERM turned into KeyboardInterrupt, MemoryError: the child goes too
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        raise
    finally:
        os.close(read_end)
    if payload is None:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        raise MeshFileError(f"{path}: the mesh reader did not finish within {limit:.0f} s: the file is malformed "
                            "(or far larger than its size suggests)")
    _, status = os.waitpid(pid, 0)
    if os.WIFSIGNALED(status):
        name = signal.Signals(os.WTERMSIG(status)).name
        raise MeshFileError(f"{path}: the mesh reader crashed ({name}) on this file: it is malformed "
                            "(e.g. a face index out of range)")
    if os.WEXITSTATUS(status) != 0 or not payload:
        raise MeshFileError(f"{path}: cannot read the mesh")
    return _receive(path, payload)


def read_time_limit(path: Path) -> float:
    """Seconds the reader child may take for the file at `path`: READ_SECONDS_BASE (or the value of
    READ_SECONDS_VARIABLE when it is a positive number) plus READ_SECONDS_PER_MB per MB of its size."""
    try:
        size = path.stat().st_size
    except OSError:
        size = 0
    try:
        base = float(os.environ.get(READ_SECONDS_VARIABLE, READ_SECONDS_BASE))
    except ValueError:
        base = READ_SECONDS_BASE
    if not 0 < base < float("inf"):
        base = READ_SECONDS_BASE
    return base + READ_SECONDS_PER_MB * size / 1e6


def _become_reader_child(parent: int) -> None:
    """In the forked child: die with the parent (SIGKILL when it exits), take SIGINT / SIGTERM by
    their default action, and send stdout and stderr to /dev/null. `parent`: the parent's pid, to
    catch a parent that died before the request took effect."""
    faulthandler.disable()  # a crash here is expected and reported by the parent, not dumped
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):  # not Linux: the parent's kill on every exception remains
        pass
    if os.getppid() != parent:
        os._exit(4)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.dup2(null, 2)
    os.close(null)


def _read_until(fd: int, deadline: float) -> Optional[bytes]:
    """Everything written to the pipe `fd` until its writer closes it, or None when `deadline`
    (time.monotonic()) passes first."""
    chunks = []
    poller = select.poll()  # not select.select: a worker may hold more than 1,024 descriptors
    poller.register(fd, select.POLLIN | select.POLLHUP)
    while True:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            return None
        if not poller.poll(min(remaining, 1.0) * 1000):
            continue
        chunk = os.read(fd, 1 << 20)
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)


def _read_with_pymeshlab(pymeshlab, path: Path):
    """("ok", vertices, faces) or ("error", message) for the file at `path` (runs in the child)."""
    meshes = pymeshlab.MeshSet()
    try:
        meshes.load_new_mesh(str(path))
    except pymeshlab.PyMeshLabException as error:
        return ("error", " ".join(str(error).split()))
    mesh = meshes.current_mesh()
    return ("ok", np.array(mesh.vertex_matrix(), dtype=np.float64),
            np.array(mesh.face_matrix(), dtype=np.int64).reshape(-1, 3))


def _send(fd: int, result) -> None:
    """Write a reader result to the pipe `fd` as one .npz (a message is sent as UTF-8 bytes)."""
    buffer = io.BytesIO()
    if result[0] == "ok":
        np.savez(buffer, vertices=result[1], faces=result[2])
    else:
        np.savez(buffer, error=np.frombuffer(result[1].encode("utf-8", "replace"), dtype=np.uint8))
    with os.fdopen(fd, "wb") as stream:
        stream.write(buffer.getvalue())


def _receive(path: Path, payload: bytes) -> Tuple[np.ndarray, np.ndarray]:
    """The arrays sent by _send, or MeshFileError with the reader's message."""
    with np.load(io.BytesIO(payload), allow_pickle=False) as arrays:
        if "error" in arrays:
            detail = arrays["error"].tobytes().decode("utf-8", "replace")
            raise MeshFileError(f"{path}: cannot read the mesh: {detail}")
        return arrays["vertices"], arrays["faces"]
