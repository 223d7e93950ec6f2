"""Names that become paths: proven to stay inside their folder, whatever the name.

Job names, frame names and output file names come from user files (a constraint file's stem, a
frame's "name"); each is checked here before it is joined to a folder, so that no name ('..', '.',
an absolute path, a separator, a NUL byte, a link pointing out) can make a run read, write or
delete anything outside the folder it was given. File names handed to libraries that take UTF-8
(MeshLab, the constraint library) are checked here too (utf8_name).
"""
from pathlib import Path

from meshik.errors import OutputError, PipelineError


def child_path(folder, name: str, what: str) -> Path:
    """`folder / name` for a single path component `name`, proven to lie inside `folder`.

    folder: the containing folder (need not exist yet). name: one component (no separators).
    what: how to describe the name in the error, e.g. "job name" or "frame name".
    Raises OutputError naming the offending name when it is empty, '.', '..', contains a path
    separator or NUL, or resolves (following existing links) to a place outside `folder`.
    """
    if not isinstance(name, str) or name in ("", ".", "..") or any(c in name for c in "/\\\0"):
        raise OutputError(f"{what} {name!r} cannot be used as a file name inside {folder}")
    return inside(folder, name, what)


def inside(folder, relative: str, what: str) -> Path:
    """`folder / relative` for a relative path (may contain '/'), proven to lie strictly inside `folder`.

    Raises OutputError naming `relative` when it is absolute, contains NUL or '..' components, or
    resolves (following existing links) to `folder` itself or outside it.
    """
    parts = Path(relative).parts if isinstance(relative, str) and "\0" not in relative else None
    if not parts or Path(relative).is_absolute() or any(p in ("..", ".") for p in parts):
        raise OutputError(f"{what} {relative!r} is not a path inside {folder}")
    base = Path(folder).resolve()
    target = (base / relative).resolve()
    if target == base or base not in target.parents:
        raise OutputError(f"{what} {relative!r} leads outside {folder}")
    return Path(folder) / relative


def utf8_name(path, error=PipelineError) -> str:
    """`path` as text, for libraries that take UTF-8 file names (MeshLab, the constraint library).

    Raises `error` (a PipelineError class) naming the file when its name is not valid UTF-8 (a
    name the file system gave as bytes, which Python holds with surrogate escapes).
    """
    text = str(path)
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise error(f"{path}: the file name is not valid UTF-8: rename the file") from None
    return text
