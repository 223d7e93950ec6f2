"""Checks of OBJ text that MeshLab's reader lets through silently.

MeshLab's OBJ reader converts coordinates with atof, so "v a b c" becomes the vertex (0, 0, 0) and
a mesh with a garbled vertex loads as if nothing were wrong. The check below finds the first vertex
line whose first three coordinates are not numbers ("nan" and "inf" count as numbers here: those
vertices are dropped by the reader and reported later), with one regular-expression pass over the
file's bytes (C speed; a million-vertex file in a fraction of a second). Its integer conversion
of face indices overflows too: "f 1 2 99999999999999999999" would be read as some triangle, so a face
index of more than nine digits (beyond any mesh MeshLab can hold) is refused with its line.
"""
import re
from pathlib import Path

from meshik.errors import MeshFileError

_NUMBER = rb"[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|(?i:nan|inf(?:inity)?))"
_GARBLED_VERTEX = re.compile(rb"^v[ \t]+(?!" + _NUMBER + rb"[ \t]+" + _NUMBER + rb"[ \t]+" + _NUMBER + rb"(?:[ \t\r]|$))"
                             rb"([^\r\n]*)", re.MULTILINE)

_HUGE_FACE_INDEX = re.compile(rb"^f[ \t][^\r\n]*?(?<![\w.])-?(\d{10,})", re.MULTILINE)


def check_obj_vertices(path: Path) -> None:
    """MeshFileError naming `path`, the line and its text when a vertex line of the OBJ file at
    `path` has a coordinate that is not a number or a face line an index of ten digits or more;
    None otherwise."""
    data = path.read_bytes()
    bad = _GARBLED_VERTEX.search(data)
    if bad:
        line = data.count(b"\n", 0, bad.start()) + 1
        text = bad.group(0)[:60].decode("utf-8", "replace")
        raise MeshFileError(f"{path}: line {line}: vertex coordinates are not three numbers: {text!r}")
    huge = _HUGE_FACE_INDEX.search(data)
    if huge:
        line = data.count(b"\n", 0, huge.start()) + 1
        raise MeshFileError(f"{path}: line {line}: face index {huge.group(1)[:30].decode('ascii')} is out of range")
