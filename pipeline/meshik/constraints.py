"""Constraint files (format "meshik-constraints", version 1): load, validate, resolve to arrays.

A constraint file names the rest mesh and the example poses, defines handle groups (vertex
indices of the rest mesh, or every rest vertex within a radius of a point), and gives per frame
the targets of the groups (one position per vertex, or a rigid motion of the group's rest
positions). A group missing from a frame keeps its previous targets (its rest positions before
the first frame that names it). The format is documented in pipeline/README.md.

    constraint_set = load("shot.json")                          # validates; ConstraintError on bad input
    resolved = resolve(constraint_set, rest_vertices)           # handle indices and #frames by #H by 3 targets

Every error is a ConstraintError whose message starts with the file name and the JSON path.
"""
import glob
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from meshik.errors import ConstraintError
from meshik.json_checks import (SchemaViolation, check_members, child, describe, expect_int, expect_list,
                                expect_number, expect_numbers, expect_object, expect_string)
from meshik.rigid import apply_rigid, axis_angle_matrix, is_rotation

FORMAT_NAME = "meshik-constraints"
FORMAT_VERSION = 1
FEATURE_SPACES = ("nonlinear", "linear")
DEFAULT_FPS = 24.0
_FRAME_NAME = re.compile(r"^[A-Za-z0-9_\-][A-Za-z0-9_.\-]{0,99}$")
_TOP_LEVEL_REQUIRED = ("format", "version", "rest", "examples", "handles", "frames")
_TOP_LEVEL_OPTIONAL = ("feature_space", "weight_regularization", "max_iterations", "tolerance", "fps")


@dataclass(frozen=True)
class IndexHandle:
    """A handle group given as vertex indices of the rest mesh."""
    vertices: Tuple[int, ...]


@dataclass(frozen=True)
class RegionHandle:
    """A handle group given as every rest vertex within `radius` of the point `near`."""
    near: Tuple[float, float, float]
    radius: float


HandleSpec = Union[IndexHandle, RegionHandle]


@dataclass(frozen=True)
class PositionTargets:
    """One target position per vertex of the group: #group vertices by 3."""
    positions: np.ndarray


@dataclass(frozen=True)
class RigidTarget:
    """A rigid motion of the group's rest positions: p -> rotation (p - center) + center + translation.

    center is None for "the centroid of the group's rest positions".
    """
    rotation: np.ndarray                 # 3 by 3
    translation: np.ndarray              # 3
    center: Optional[np.ndarray]         # 3, or None


TargetSpec = Union[PositionTargets, RigidTarget]


@dataclass(frozen=True)
class Frame:
    """One frame: its name (used in output file names) and the groups it moves."""
    name: str
    targets: Dict[str, TargetSpec]


@dataclass(frozen=True)
class ConstraintSet:
    """A validated constraint file. Paths are absolute; options left out of the file are None."""
    source: Path
    rest: Path
    examples: Tuple[Path, ...]
    handles: Dict[str, HandleSpec]
    frames: Tuple[Frame, ...]
    feature_space: Optional[str] = None
    weight_regularization: Optional[float] = None
    max_iterations: Optional[int] = None
    tolerance: Optional[float] = None
    fps: float = DEFAULT_FPS

    def solver_options(self) -> Dict[str, Any]:
        """The solver keyword arguments the file sets (feature_space, weight_regularization, ...)."""
        names = ("feature_space", "weight_regularization", "max_iterations", "tolerance")
        return {name: getattr(self, name) for name in names if getattr(self, name) is not None}


@dataclass(frozen=True)
class ResolvedConstraints:
    """Handle groups resolved against a rest mesh.

    groups:      group name -> vertex indices of the group (in the file's order)
    handles:     #H vertex indices, the groups concatenated in the order of the file
    targets:     #frames by #H by 3 target positions, in the order of `handles`
    frame_names: #frames names
    """
    groups: Dict[str, np.ndarray]
    handles: np.ndarray
    targets: np.ndarray
    frame_names: Tuple[str, ...]


def load(path) -> ConstraintSet:
    """Read and validate a constraint file. Raises ConstraintError naming the file and JSON path.

    Checks the schema, and that the rest and example files exist (relative paths are taken from
    the constraint file's folder). Handle indices are range-checked later, by resolve().
    """
    path = Path(path)
    try:
        text = path.read_bytes().decode("utf-8")
    except FileNotFoundError:
        raise ConstraintError(f"{path}: constraint file not found") from None
    except OSError as error:
        raise ConstraintError(f"{path}: cannot read the constraint file: {error.strerror or error}") from None
    except UnicodeDecodeError as error:
        raise ConstraintError(f"{path}: not UTF-8 text (byte {error.start})") from None
    return loads(text, path)


def loads(text: str, source) -> ConstraintSet:
    """Validate constraint-file text; `source` is the file's path (names it, and anchors relative paths)."""
    source = Path(source)
    try:
        document = json.loads(text, parse_constant=_parse_constant)
    except json.JSONDecodeError as error:
        raise ConstraintError(f"{source}: not valid JSON: line {error.lineno} column {error.colno}: {error.msg}") from None
    except RecursionError:
        raise ConstraintError(f"{source}: JSON nested too deeply") from None
    try:
        return _parse_document(document, source)
    except SchemaViolation as violation:
        raise ConstraintError(f"{source}: {violation.path or 'top level'}: {violation.problem}") from None


def _parse_constant(name: str) -> float:
    """json.loads hook for the non-standard NaN / Infinity literals: parsed, then refused by the checks."""
    return float(name.replace("Infinity", "inf"))


def _parse_document(document: Any, source: Path) -> ConstraintSet:
    """ConstraintSet from a parsed JSON document; raises SchemaViolation."""
    top = expect_object(document, "")
    check_members(top, "", _TOP_LEVEL_REQUIRED, _TOP_LEVEL_OPTIONAL)
    if top["format"] != FORMAT_NAME:
        raise SchemaViolation("format", f'expected "{FORMAT_NAME}", got {describe(top["format"])}')
    version = expect_int(top["version"], "version", 1, what="an integer version")
    if version != FORMAT_VERSION:
        raise SchemaViolation("version", f"version {version} is not supported (this MeshIK reads version {FORMAT_VERSION})")
    base = source.parent
    rest = _existing_file(base, expect_string(top["rest"], "rest"), "rest")
    examples = _example_paths(top["examples"], base, rest)
    handles = _parse_handles(top["handles"])
    frames = _parse_frames(top["frames"], handles)
    options = _parse_options(top)
    return ConstraintSet(source=source.resolve(), rest=rest, examples=examples, handles=handles, frames=frames, **options)


def _parse_options(top: Dict[str, Any]) -> Dict[str, Any]:
    """The optional solver and animation settings present in the top-level object."""
    options: Dict[str, Any] = {}
    if "feature_space" in top:
        value = expect_string(top["feature_space"], "feature_space")
        if value not in FEATURE_SPACES:
            raise SchemaViolation("feature_space", f'expected "nonlinear" or "linear", got "{value}"')
        options["feature_space"] = value
    if "weight_regularization" in top:
        options["weight_regularization"] = expect_number(top["weight_regularization"], "weight_regularization", 0.0)
    if "max_iterations" in top:
        options["max_iterations"] = expect_int(top["max_iterations"], "max_iterations", 1)
    if "tolerance" in top:
        options["tolerance"] = expect_number(top["tolerance"], "tolerance", 0.0, exclusive_minimum=True)
    if "fps" in top:
        options["fps"] = expect_number(top["fps"], "fps", 0.0, exclusive_minimum=True)
    return options


def _existing_file(base: Path, name: str, path: str) -> Path:
    """Absolute path of `name` (relative to `base` unless absolute); SchemaViolation when it is no file."""
    try:
        resolved = (base / name).resolve()
        found = resolved.is_file()
    except (OSError, ValueError) as error:  # name too long, NUL or unencodable characters
        raise SchemaViolation(path, f"unusable file name: {error}") from None
    if not found:
        raise SchemaViolation(path, f"mesh file not found: {resolved}")
    return resolved


def _example_paths(value: Any, base: Path, rest: Path) -> Tuple[Path, ...]:
    """Example mesh paths from a list of names or a glob string (matches sorted by their numbers)."""
    if isinstance(value, str):
        pattern = expect_string(value, "examples")
        try:
            matches = {Path(p).resolve() for p in glob.glob(str(base / pattern))}
            matches = sorted((p for p in matches if p.is_file() and p != rest), key=_natural_key)
        except (OSError, ValueError) as error:
            raise SchemaViolation("examples", f"unusable glob pattern: {error}") from None
        if not matches:
            raise SchemaViolation("examples", f'glob "{pattern}" matches no mesh file besides the rest mesh (in {base})')
        return tuple(matches)
    names = expect_list(value, "examples", non_empty=True)
    return tuple(_existing_file(base, expect_string(name, child("examples", i)), child("examples", i))
                 for i, name in enumerate(names))


def _natural_key(path: Path):
    """Sort key that orders 'pose2' before 'pose10'."""
    return [(0, int(part), "") if part.isdigit() else (1, 0, part) for part in re.split(r"(\d+)", str(path))]


def _parse_handles(value: Any) -> Dict[str, HandleSpec]:
    """Handle groups by name, in the file's order: vertex-index lists or {near, radius} regions."""
    groups = expect_object(value, "handles")
    handles: Dict[str, HandleSpec] = {}
    owner: Dict[int, str] = {}
    for name, spec in groups.items():
        path = child("handles", name)
        if name.startswith("_"):
            continue  # the user's own annotation
        if not name.strip():
            raise SchemaViolation(path, "handle group names must not be empty")
        if isinstance(spec, dict):
            check_members(spec, path, ("near", "radius"), ())
            near = expect_numbers(spec["near"], child(path, "near"), 3)
            radius = expect_number(spec["radius"], child(path, "radius"), 0.0, exclusive_minimum=True)
            handles[name] = RegionHandle(near=near, radius=radius)
            continue
        if not isinstance(spec, list):
            raise SchemaViolation(path, f"expected a list of vertex indices or a region {{\"near\", \"radius\"}}, got {describe(spec)}")
        indices = expect_list(spec, path, non_empty=True)
        for i, index in enumerate(indices):
            expect_int(index, child(path, i), 0, what="a vertex index")
            if index in owner:
                where = "earlier in this group" if owner[index] == name else f'in handle group "{owner[index]}"'
                raise SchemaViolation(child(path, i), f"vertex {index} is already a handle {where}")
            owner[index] = name
        handles[name] = IndexHandle(vertices=tuple(indices))
    if not handles:
        raise SchemaViolation("handles", "expected at least one handle group")
    return handles


def _parse_frames(value: Any, handles: Dict[str, HandleSpec]) -> Tuple[Frame, ...]:
    """Frames with their target specs; names default to the 1-based frame number, zero-padded."""
    frames = expect_list(value, "frames", non_empty=True)
    parsed: List[Frame] = []
    seen: Dict[str, int] = {}
    for number, frame in enumerate(frames):
        path = child("frames", number)
        frame = expect_object(frame, path)
        check_members(frame, path, (), ("name", "targets"))
        name = expect_string(frame["name"], child(path, "name")) if "name" in frame else f"{number + 1:04d}"
        if not _FRAME_NAME.match(name):
            raise SchemaViolation(child(path, "name"), f'"{name}" cannot be a file name: use letters, digits, ".", "_", "-" (at most 100)')
        if name in seen:
            raise SchemaViolation(child(path, "name"), f'"{name}" is also the name of frames[{seen[name]}]')
        seen[name] = number
        targets = expect_object(frame.get("targets", {}), child(path, "targets"))
        parsed.append(Frame(name=name, targets={group: _parse_target(spec, handles, group, child(child(path, "targets"), group))
                                                for group, spec in targets.items() if not group.startswith("_")}))
    return tuple(parsed)


def _parse_target(spec: Any, handles: Dict[str, HandleSpec], group: str, path: str) -> TargetSpec:
    """A group's target in one frame: a list of positions or a rigid motion object."""
    if group not in handles:
        known = ", ".join(f'"{name}"' for name in handles)
        raise SchemaViolation(path, f'no handle group named "{group}" (groups: {known})')
    if isinstance(spec, dict):
        return _parse_rigid(spec, path)
    if not isinstance(spec, list):
        raise SchemaViolation(path, f"expected a list of [x, y, z] positions or a rigid motion object, got {describe(spec)}")
    handle = handles[group]
    if isinstance(handle, IndexHandle) and len(spec) != len(handle.vertices):
        raise SchemaViolation(path, f"expected {len(handle.vertices)} positions (one per handle vertex), got {len(spec)}")
    if not spec:
        raise SchemaViolation(path, "expected at least one position")
    return PositionTargets(positions=np.array([expect_numbers(p, child(path, i), 3) for i, p in enumerate(spec)]))


def _parse_rigid(spec: Dict[str, Any], path: str) -> RigidTarget:
    """A rigid motion: "matrix" (4 by 4, rows), or "rotate" and/or "translate" (rotation applied first)."""
    check_members(spec, path, (), ("translate", "rotate", "matrix"))
    if "matrix" in spec:
        if "translate" in spec or "rotate" in spec:
            raise SchemaViolation(path, '"matrix" cannot be combined with "translate" or "rotate"')
        return _parse_matrix(spec["matrix"], child(path, "matrix"))
    if "translate" not in spec and "rotate" not in spec:
        raise SchemaViolation(path, 'expected "translate", "rotate" or "matrix"')
    translation = np.array(expect_numbers(spec["translate"], child(path, "translate"), 3)) if "translate" in spec else np.zeros(3)
    rotation, center = np.eye(3), None
    if "rotate" in spec:
        rotate_path = child(path, "rotate")
        rotate = expect_object(spec["rotate"], rotate_path)
        check_members(rotate, rotate_path, ("axis", "degrees"), ("center",))
        axis = expect_numbers(rotate["axis"], child(rotate_path, "axis"), 3)
        if not math.isfinite(math.hypot(*axis)) or math.hypot(*axis) < 1e-12:
            raise SchemaViolation(child(rotate_path, "axis"), "the rotation axis must have a non-zero, finite length")
        degrees = expect_number(rotate["degrees"], child(rotate_path, "degrees"))
        rotation = axis_angle_matrix(axis, degrees)
        if "center" in rotate:
            center = np.array(expect_numbers(rotate["center"], child(rotate_path, "center"), 3))
    return RigidTarget(rotation=rotation, translation=translation, center=center)


def _parse_matrix(value: Any, path: str) -> RigidTarget:
    """A 4 by 4 row-major rigid transform [[R t], [0 0 0 1]] as a RigidTarget about the origin."""
    rows = value if isinstance(value, list) and len(value) == 4 else None
    if rows is None:
        raise SchemaViolation(path, f"expected 4 rows of 4 numbers, got {describe(value)}")
    matrix = np.array([expect_numbers(row, child(path, i), 4) for i, row in enumerate(rows)])
    if not np.allclose(matrix[3], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        raise SchemaViolation(child(path, 3), "expected the last row [0, 0, 0, 1]")
    if not is_rotation(matrix[:3, :3]):
        raise SchemaViolation(path, "not a rigid motion: the upper-left 3 by 3 block is not a rotation")
    return RigidTarget(rotation=matrix[:3, :3], translation=matrix[:3, 3], center=np.zeros(3))


def resolve(constraints: ConstraintSet, rest_vertices: np.ndarray) -> ResolvedConstraints:
    """Handle indices and per-frame targets for a rest mesh (#V by 3). Raises ConstraintError.

    Checks indices against #V, finds region vertices, checks that position lists match region
    sizes, that no vertex is in two groups, and applies rigid motions to the groups' rest positions.
    """
    try:
        groups = _resolve_groups(constraints.handles, rest_vertices)
        return _resolve_targets(constraints, groups, rest_vertices)
    except SchemaViolation as violation:
        raise ConstraintError(f"{constraints.source}: {violation.path}: {violation.problem}") from None


def _resolve_groups(handles: Dict[str, HandleSpec], rest_vertices: np.ndarray) -> Dict[str, np.ndarray]:
    """Vertex indices of each group; SchemaViolation for out-of-range, empty or overlapping groups."""
    count = len(rest_vertices)
    groups: Dict[str, np.ndarray] = {}
    owner = np.full(count, -1)
    for number, (name, spec) in enumerate(handles.items()):
        path = child("handles", name)
        if isinstance(spec, IndexHandle):
            for i, index in enumerate(spec.vertices):
                if index >= count:
                    raise SchemaViolation(child(path, i), f"vertex {index} is out of range (the rest mesh has {count} vertices)")
            indices = np.array(spec.vertices, dtype=np.int64)
        else:
            distance = np.linalg.norm(rest_vertices - np.array(spec.near), axis=1)
            indices = np.flatnonzero(distance <= spec.radius)
            if len(indices) == 0:
                raise SchemaViolation(path, f"no rest vertex within radius {spec.radius:g} of [{', '.join(f'{c:g}' for c in spec.near)}] "
                                            f"(the nearest is {distance.min():.6g} away)")
        taken = indices[owner[indices] >= 0]
        if len(taken):
            other = list(handles)[owner[taken[0]]]
            raise SchemaViolation(path, f'vertex {taken[0]} is also in handle group "{other}"')
        owner[indices] = number
        groups[name] = indices
    return groups


def _resolve_targets(constraints: ConstraintSet, groups: Dict[str, np.ndarray], rest_vertices: np.ndarray) -> ResolvedConstraints:
    """Per-frame targets (#frames by #H by 3), each group carrying its previous targets forward."""
    current = {name: rest_vertices[indices].astype(float) for name, indices in groups.items()}
    frames = []
    for number, frame in enumerate(constraints.frames):
        for name, spec in frame.targets.items():
            path = child(child(child("frames", number), "targets"), name)
            current[name] = _group_targets(spec, rest_vertices[groups[name]], path)
        frames.append(np.concatenate([current[name] for name in groups]))
    handles = np.concatenate(list(groups.values())) if groups else np.zeros(0, dtype=np.int64)
    return ResolvedConstraints(groups=groups, handles=handles, targets=np.stack(frames),
                               frame_names=tuple(frame.name for frame in constraints.frames))


def _group_targets(spec: TargetSpec, rest_positions: np.ndarray, path: str) -> np.ndarray:
    """#group vertices by 3 targets of one group in one frame, from its spec and rest positions."""
    if isinstance(spec, PositionTargets):
        if len(spec.positions) != len(rest_positions):
            raise SchemaViolation(path, f"expected {len(rest_positions)} positions (one per handle vertex), got {len(spec.positions)}")
        return spec.positions
    center = rest_positions.mean(axis=0) if spec.center is None else spec.center
    return apply_rigid(rest_positions, spec.rotation, spec.translation, center)
