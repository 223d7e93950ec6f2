"""Reading mesh files without trusting the reader: checks first, then MeshLab's reader in a child.

Some of MeshLab's readers crash the process on malformed files (an OBJ or OFF face index out of
range is a segmentation fault inside the reader). A crash must not take the CLI, a batch worker or
a notebook down with it, nor be reported as "killed by signal 11": the reader runs in a forked
child process that sends the arrays back through a pipe, and a child that dies is reported as a
malformed file, naming it.
"""
import faulthandler
import io
import os
import signal
import stat
from pathlib import Path
from typing import Tuple

import numpy as np

from meshik.errors import MeshFileError
from meshik.inputs.meshlab_module import pymeshlab_module
from meshik.outputs.safe_paths import utf8_name

# Mesh files larger than this are refused before reading (a bound on memory, and /dev/zero).
MAX_INPUT_BYTES = 4 << 30


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


def isolated_load(path: Path) -> Tuple[np.ndarray, np.ndarray]:
    """(#V by 3 float64 positions, #F by 3 int64 triangles) read by pymeshlab in a forked child.

    Raises MeshFileError naming `path` when the reader refuses the file or dies on it.
    """
    pymeshlab = pymeshlab_module()  # imported before the fork, so the child does not import it again

    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: read, send, and leave without running the parent's clean-up
        os.close(read_end)
        faulthandler.disable()  # a crash here is expected and reported by the parent, not dumped
        status = 0
        try:
            _send(write_end, _read_with_pymeshlab(pymeshlab, path))
        except BaseException:
            status = 3
        os._exit(status)
    os.close(write_end)
    with os.fdopen(read_end, "rb") as stream:
        payload = stream.read()
    _, status = os.waitpid(pid, 0)
    if os.WIFSIGNALED(status):
        name = signal.Signals(os.WTERMSIG(status)).name
        raise MeshFileError(f"{path}: the mesh reader crashed ({name}) on this file: it is malformed "
                            "(e.g. a face index out of range)")
    if os.WEXITSTATUS(status) != 0 or not payload:
        raise MeshFileError(f"{path}: cannot read the mesh")
    return _receive(path, payload)


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
