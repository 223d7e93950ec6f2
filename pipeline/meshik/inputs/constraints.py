"""Constraint files (format "meshik-constraints", version 1): load, validate, resolve to arrays.

A thin wrapper over the C++ constraint-file library (cpp_core/constraints, bound as
meshik._constraints), the one implementation the MeshLab plugins use too. A constraint file names
the rest mesh and the example poses, defines handle groups (vertex indices of the rest mesh, or
every rest vertex within a radius of a point), and gives per frame the targets of the groups (one
position per vertex, or a rigid motion of the group's rest positions). A group missing from a frame
keeps its previous targets (its rest positions before the first frame that names it). The format
is documented in pipeline/README.md; its JSON Schema is meshik/schema/meshik-constraints-1.schema.json.

    constraint_set = load("shot.json")                          # validates; ConstraintError on bad input
    resolved = resolve(constraint_set, rest_vertices)           # handle indices and #frames by #H by 3 targets
    problems = validate("shot.json")                            # every problem as a message, [] when good

Every error is a ConstraintError whose message starts with the file name and the JSON path.
"""
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from meshik import _constraints
from meshik.errors import ConstraintError
from meshik.outputs.safe_paths import utf8_name

FORMAT_NAME = "meshik-constraints"
FORMAT_VERSION = 1
FEATURE_SPACES = ("nonlinear", "linear")
BLENDS = ("affine", "free")
DEFAULT_FPS = 24.0
SCHEMA_PATH = Path(__file__).resolve().parents[1] / "schema" / "meshik-constraints-1.schema.json"


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
    """A validated constraint file. Paths are absolute; options left out of the file are None.

    document is the library's checked document (what resolve() works from).
    """
    source: Path
    rest: Path
    examples: Tuple[Path, ...]
    handles: Dict[str, HandleSpec]
    frames: Tuple[Frame, ...]
    feature_space: Optional[str] = None
    blend: Optional[str] = None
    # a region count, "auto", or vertex groups: name -> rest vertex indices
    regions: Union[None, int, str, Dict[str, Tuple[int, ...]]] = None
    region_smoothness: Optional[float] = None
    weight_regularization: Optional[float] = None
    handle_stiffness: Optional[float] = None
    max_iterations: Optional[int] = None
    tolerance: Optional[float] = None
    fps: float = DEFAULT_FPS
    document: Any = field(default=None, repr=False, compare=False)

    def solver_options(self) -> Dict[str, Any]:
        """The solver keyword arguments the file sets (feature_space, blend, regions, ...); vertex-group
        regions stay a dict here (region_vertex_groups turns them into meshik.Solver's array)."""
        names = ("feature_space", "blend", "regions", "region_smoothness", "weight_regularization", "handle_stiffness",
                 "max_iterations", "tolerance")
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

    Checks the format, and that the rest and example files exist (relative paths are taken from
    the constraint file's folder). Handle indices are range-checked later, by resolve().
    """
    path = Path(path)
    return _constraint_set(_constraints.read(utf8_name(path, ConstraintError)), path)


def loads(text: str, source) -> ConstraintSet:
    """Validate constraint-file text; `source` is the file's path (names it, and anchors relative paths)."""
    source = Path(source)
    try:
        data = text.encode("utf-8")
    except UnicodeEncodeError as error:
        raise ConstraintError(f"{source}: not UTF-8 text (character {error.start})") from None
    return _constraint_set(_constraints.parse(data, str(source)), source)


def validate(path) -> List[str]:
    """Every problem of the constraint file at `path` (format and mesh files), one message each; [] when good."""
    try:
        return list(_constraints.validate(utf8_name(path, ConstraintError), True))
    except ConstraintError as error:
        return [str(error)]


def resolve(constraints: ConstraintSet, rest_vertices: np.ndarray) -> ResolvedConstraints:
    """Handle indices and per-frame targets for a rest mesh (#V by 3). Raises ConstraintError.

    Checks indices against #V, finds region vertices, checks that position lists match region
    sizes, that no vertex is in two groups, and applies rigid motions to the groups' rest positions.
    """
    rest = np.ascontiguousarray(rest_vertices, dtype=np.float64)
    if rest.ndim != 2 or rest.shape[1] != 3:
        raise ValueError(f"rest_vertices must have shape (n, 3), got {rest.shape}")
    names, groups, handles, targets, frame_names = _constraints.resolve(constraints.document, rest)
    return ResolvedConstraints(groups=dict(zip(names, groups)), handles=handles, targets=targets,
                               frame_names=tuple(frame_names))


def write(path, rest: str, examples: Sequence[str], groups: Dict[str, Tuple[np.ndarray, np.ndarray]],
          frame_name: str = "0001") -> None:
    """Write a one-frame constraint file: groups maps a name to (#group vertex indices, #group by 3 targets).

    rest and examples are written as given (relative to the file's folder, or absolute). The file
    is checked before it replaces `path`; raises ConstraintError.
    """
    content = [(name, np.ascontiguousarray(vertices, dtype=np.int64).reshape(-1),
                np.ascontiguousarray(targets, dtype=np.float64).reshape(-1, 3)) for name, (vertices, targets) in groups.items()]
    _constraints.write(utf8_name(path, ConstraintError), rest, list(examples), content, frame_name)


def _constraint_set(document, source: Path) -> ConstraintSet:
    """A ConstraintSet from the library's document, with its mesh files found on disk."""
    rest, examples = _constraints.locate_mesh_files(document)
    return ConstraintSet(
        source=source.resolve(), rest=Path(rest), examples=tuple(Path(p) for p in examples),
        handles={group.name: _handle_spec(group) for group in document.handles},
        frames=tuple(Frame(name=frame.name, targets={target.group: _target_spec(target) for target in frame.targets})
                     for frame in document.frames),
        feature_space=document.feature_space, blend=document.blend, regions=_regions(document.regions),
        region_smoothness=document.region_smoothness, weight_regularization=document.weight_regularization,
        handle_stiffness=document.handle_stiffness, max_iterations=document.max_iterations,
        tolerance=document.tolerance, fps=document.fps, document=document)


def region_vertex_groups(groups: Dict[str, Sequence[int]], num_vertices: int, source) -> np.ndarray:
    """#V region ids (-1: in no group) of vertex groups (name -> rest vertex indices), in the
    groups' order. Raises ConstraintError naming the file (source) and group of an index out of range."""
    regions = np.full(num_vertices, -1, dtype=np.int64)
    for number, (name, vertices) in enumerate(groups.items()):
        vertices = np.asarray(vertices, dtype=np.int64)
        bad = vertices[(vertices < 0) | (vertices >= num_vertices)]
        if len(bad):
            raise ConstraintError(f"{source}: regions.{name}: vertex {int(bad[0])} is out of range "
                                  f"(the rest mesh has {num_vertices} vertices)")
        regions[vertices] = number
    return regions


def _regions(setting) -> Union[None, int, str, Dict[str, Tuple[int, ...]]]:
    """The file's "regions" (the library's RegionSetting or None) as ConstraintSet.regions."""
    if setting is None:
        return None
    if setting.automatic:
        return "auto"
    if setting.groups:
        return {group.name: tuple(group.vertices) for group in setting.groups}
    return int(setting.count)


def _handle_spec(group) -> HandleSpec:
    """IndexHandle or RegionHandle of one of the library's handle groups."""
    if group.near is not None:
        return RegionHandle(near=tuple(group.near), radius=group.radius)
    return IndexHandle(vertices=tuple(group.vertices))


def _target_spec(target) -> TargetSpec:
    """PositionTargets or RigidTarget of one of the library's group targets."""
    if not target.rigid:
        return PositionTargets(positions=np.array(target.positions, dtype=np.float64).reshape(-1, 3))
    center = None if target.center is None else np.array(target.center)
    return RigidTarget(rotation=np.array(target.rotation).reshape(3, 3), translation=np.array(target.translation), center=center)
