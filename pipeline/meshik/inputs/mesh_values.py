"""Checks of mesh files for what MeshLab's readers get wrong silently or never finish on.

- A vertex with a NaN or infinite coordinate: the readers drop it and shift every later vertex
  index, so handles and examples silently address other vertices. Text files (OBJ, OFF, ASCII PLY
  and STL) are scanned for such numbers and the first is named with its line; binary STL and
  binary PLY vertex blocks are read with numpy and the first bad vertex is named.
- An STL that is neither binary (84 bytes plus 50 per facet its header gives) nor ASCII text: the
  reader takes it for ASCII and loops forever (100 zero bytes, a truncated binary file).
Each check reads the file once with C-speed passes (byte searches and numpy first; a regular
expression only where those find a candidate).
"""
import re
from pathlib import Path
from typing import Optional

import numpy as np

from meshik.errors import MeshFileError

# A NaN or infinity spelled out, or a decimal whose exponent may overflow a double (checked below).
_SUSPECT_NUMBER = re.compile(rb"(?<![\w.+-])[-+]?(?:(?i:nan|inf(?:inity)?)|(?:\d+\.?\d*|\.\d+)[eE]\+?\d{3,})(?![\w.])")
_PLY_SCALARS = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
                "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
                "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def check_mesh_values(path: Path, data: bytes) -> None:
    """MeshFileError naming `path` and the line or vertex of the first non-finite coordinate of the
    mesh file whose bytes are `data`, or naming why an STL cannot be read; None when none is found.
    The format is taken from the suffix (.obj, .off, .ply, .stl); other formats are not checked."""
    suffix = path.suffix.lower()
    if suffix == ".stl":
        _check_stl(path, data)
    elif suffix == ".ply":
        _check_ply(path, data)
    elif suffix == ".obj":
        _check_text(path, data, 0, vertex_lines=True)
    elif suffix == ".off":
        _check_text(path, data, 0, vertex_lines=False)


def _check_text(path: Path, data: bytes, start: int, vertex_lines: bool) -> None:
    """MeshFileError at the first non-finite number from byte `start` on, outside '#' comments
    (vertex_lines: only on OBJ vertex lines, 'v x y z')."""
    if not _may_hold_non_finite(data[start:]):
        return
    for match in _SUSPECT_NUMBER.finditer(data, start):
        line_start = data.rfind(b"\n", 0, match.start()) + 1
        head = data[line_start:line_start + 2]
        if head.startswith(b"#") or (vertex_lines and head not in (b"v ", b"v\t")):
            continue
        if np.isfinite(float(match.group(0))):
            continue
        line = data.count(b"\n", 0, match.start()) + 1
        raise MeshFileError(f"{path}: line {line}: the coordinate {match.group(0).decode('ascii')} is not a finite "
                            "number (MeshLab would drop this vertex and shift every later vertex index)")


def _may_hold_non_finite(data: bytes) -> bool:
    """Whether `data` holds "nan" or "inf" in any case, or an exponent of three digits or more
    ("e+308", "E999"): a byte-level pass about 20 times faster than the regular expression, which
    then runs only on files that may hold such a number."""
    lowered = data.lower()
    if b"nan" in lowered or b"inf" in lowered:
        return True
    codes = np.frombuffer(lowered, dtype=np.uint8)
    exponent = np.flatnonzero(codes[:-3] == ord("e")) + 1
    exponent += codes[exponent] == ord("+")
    exponent = exponent[exponent + 2 < len(codes)]
    digits = [(codes[exponent + k] >= ord("0")) & (codes[exponent + k] <= ord("9")) for k in range(3)]
    return bool((digits[0] & digits[1] & digits[2]).any())


def _check_stl(path: Path, data: bytes) -> None:
    """MeshFileError unless `data` is a whole binary STL with finite coordinates or ASCII STL text
    with finite numbers."""
    facets = int.from_bytes(data[80:84], "little") if len(data) >= 84 else None
    if facets is not None and len(data) == 84 + 50 * facets:
        records = np.frombuffer(data, dtype=np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")]),
                                count=facets, offset=84)
        bad = np.flatnonzero(~np.isfinite(records["corners"]).reshape(facets, -1).all(axis=1))
        if len(bad):
            raise MeshFileError(f"{path}: facet {bad[0]} has a corner with a coordinate that is not a finite number")
        return
    if data.lstrip()[:5].lower() != b"solid" or b"\0" in data:
        expected = f" ({84 + 50 * facets} bytes for the {facets} facets its header gives, {len(data)} found)" \
            if facets is not None else f" (only {len(data)} bytes)"
        raise MeshFileError(f"{path}: malformed STL: neither a whole binary STL{expected} nor ASCII STL text "
                            "starting with 'solid'")
    _check_text(path, data, 0, vertex_lines=False)


def _check_ply(path: Path, data: bytes) -> None:
    """MeshFileError at the first non-finite coordinate of a PLY file's vertex element (ASCII: by
    line; binary: by vertex, when the vertex element comes first and has no list properties)."""
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        return  # the reader names what is wrong with the header
    body = data.index(b"\n", end) + 1 if b"\n" in data[end:] else len(data)
    header = data[:end].decode("ascii", "replace").split("\n")
    formats = [line.split()[1] for line in header if line.startswith("format ") and len(line.split()) > 1]
    if formats and formats[0] == "ascii":
        _check_text(path, data, body, vertex_lines=False)
        return
    vertex_type = _ply_vertex_type(header, ">" if formats and formats[0] == "binary_big_endian" else "<")
    if vertex_type is None:
        return
    dtype, count = vertex_type
    count = min(count, (len(data) - body) // dtype.itemsize)  # a short file is the reader's to refuse
    vertices = np.frombuffer(data, dtype=dtype, count=count, offset=body)
    coordinates = np.stack([vertices[axis].astype(np.float64) for axis in "xyz" if axis in dtype.names], axis=1)
    bad = np.flatnonzero(~np.isfinite(coordinates).all(axis=1))
    if len(bad):
        raise MeshFileError(f"{path}: vertex {bad[0]} has a coordinate that is not a finite number (MeshLab would drop "
                            "it and shift every later vertex index)")


def _ply_vertex_type(header, order: str) -> Optional[tuple]:
    """(numpy record dtype, count) of a binary PLY's vertex element when it is the first element and
    has only scalar properties; None otherwise. header: the header's lines; order: '<' or '>'."""
    fields, count, first = [], None, True
    for line in header:
        words = line.split()
        if words[:1] == ["element"]:
            if count is not None or not first:
                break
            first = False
            if len(words) != 3 or words[1] != "vertex" or not words[2].isdigit():
                return None
            count = int(words[2])
        elif words[:1] == ["property"] and count is not None:
            if len(words) != 3 or words[1] not in _PLY_SCALARS:
                return None
            fields.append((words[2], order + _PLY_SCALARS[words[1]]))
    if count is None or not fields or len({name for name, _ in fields}) != len(fields):
        return None
    return np.dtype(fields), count
