"""Replacing a whole folder by another in one directory-entry swap (Linux renameat2).

A job folder inside a batch's output folder is committed this way: the new result is built in a
sibling folder, everything in the old folder that the new result must keep (files the earlier run
did not provably write: a user's notes, a file the user edited) is hard-linked into it, and one
renameat2(RENAME_EXCHANGE) swaps the two names. A reader, or a run killed at any instant, sees the
complete old folder or the complete new one, never a mix, and the old folder's name is then a
sibling that holds only the earlier run's own outputs and second links of the kept files.
"""
import ctypes
import errno
import os
import stat
from pathlib import Path
from typing import Callable, Optional

_AT_FDCWD = -100
_RENAME_NOREPLACE = 1
_RENAME_EXCHANGE = 2


class SwapUnavailable(OSError):
    """This system or file system cannot swap or hard-link here; the caller commits another way."""


def _renameat2() -> Optional[Callable]:
    """glibc's renameat2, or None where the C library has none."""
    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError):
        return None
    function.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    function.restype = ctypes.c_int
    return function


_RENAMEAT2 = _renameat2()


def swap_in(new: Path, destination: Path) -> None:
    """Put folder `new` at `destination` in one step; the old folder (if any) ends up at `new`'s name.

    SwapUnavailable where the system or file system has no atomic exchange (the caller falls back);
    OSError for any other failure, with nothing moved.
    """
    if _RENAMEAT2 is None:
        raise SwapUnavailable(errno.ENOSYS, "renameat2 is not available")
    flags = _RENAME_EXCHANGE if os.path.lexists(destination) else _RENAME_NOREPLACE
    if _RENAMEAT2(_AT_FDCWD, os.fsencode(new), _AT_FDCWD, os.fsencode(destination), flags) == 0:
        return
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.EXDEV, errno.ENOTSUP):
        raise SwapUnavailable(code, os.strerror(code))
    raise OSError(code, os.strerror(code), str(destination))


def carry_over(old: Path, new: Path, replaced: Callable[[str], bool]) -> None:
    """Hard-link into `new` every entry of folder `old` that the new result must keep.

    An entry is kept unless `replaced(relative)` says the swap may drop it (the new result has a
    file of that name, or the earlier run provably wrote it), or `new` already has that path.
    Folders are recreated, files hard-linked and symbolic links copied as links, so `old` keeps
    everything until it is removed after the swap. SwapUnavailable when an entry cannot be kept
    that way (another file system, no hard links, a FIFO or device): the caller falls back.
    """
    for folder, subfolders, files in os.walk(old):
        relative_folder = Path(folder).relative_to(old)
        for name in subfolders + files:
            relative = (relative_folder / name).as_posix()
            source, target = Path(folder) / name, new / relative
            if replaced(relative) or os.path.lexists(target):
                continue
            mode = source.lstat().st_mode
            if not (stat.S_ISLNK(mode) or stat.S_ISDIR(mode) or stat.S_ISREG(mode)):
                raise SwapUnavailable(errno.ENOTSUP, f"{source} is neither a file, a folder nor a link")
            try:
                if stat.S_ISLNK(mode):
                    os.symlink(os.readlink(source), target)
                elif stat.S_ISDIR(mode):
                    target.mkdir()
                else:
                    os.link(source, target)
            except OSError as error:
                if error.errno in (errno.EXDEV, errno.EPERM, errno.EMLINK, errno.ENOTSUP):
                    raise SwapUnavailable(error.errno, f"cannot keep {source}: {error.strerror}") from None
                raise
