"""Checks of OBJ text that MeshLab's reader lets through silently.

MeshLab's OBJ reader converts coordinates with atof, so "v a b c" becomes the vertex (0, 0, 0) and
a mesh with a garbled vertex loads as if nothing were wrong. The check below finds the first vertex
line whose first three coordinates are not numbers ("nan" and "inf" count as numbers here: those
vertices are dropped by the reader and reported later), with one regular-expression pass over the
file's bytes (C speed; a million-vertex file in a fraction of a second).
"""
import re
from pathlib import Path

from meshik.errors import MeshFileError

_NUMBER = rb"[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|(?i:nan|inf(?:inity)?))"
_GARBLED_VERTEX = re.compile(rb"^v[ \t]+(?!" + _NUMBER + rb"[ \t]+" + _NUMBER + rb"[ \t]+" + _NUMBER + rb"(?:[ \t\r]|$))"
                             rb"([^\r\n]*)", re.MULTILINE)


def check_obj_vertices(path: Path) -> None:
    """MeshFileError naming `path`, the line and its text when a vertex line of the OBJ file at
    `path` has a coordinate that is not a number; None otherwise."""
    data = path.read_bytes()
    bad = _GARBLED_VERTEX.search(data)
    if bad:
        line = data.count(b"\n", 0, bad.start()) + 1
        text = bad.group(0)[:60].decode("utf-8", "replace")
        raise MeshFileError(f"{path}: line {line}: vertex coordinates are not three numbers: {text!r}")
