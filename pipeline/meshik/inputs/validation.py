"""`meshik validate`: every problem of constraint files, not only the first.

The format and the mesh files are checked by the constraint-file library (meshik.inputs.constraints);
a file without such problems is then resolved against its rest mesh, which finds vertex indices
out of range, empty regions and groups that overlap.
"""
from typing import Iterable, List

from meshik.inputs import constraints
from meshik.errors import PipelineError


def validate_files(paths: Iterable) -> List[List[str]]:
    """For each constraint file in `paths`, the list of its problems as messages ([] when it is good)."""
    return [_problems(path) for path in paths]


def _problems(path) -> List[str]:
    """The problems of one constraint file: the library's, else those of resolving on the rest mesh."""
    problems = constraints.validate(path)
    if problems:
        return problems
    from meshik.inputs.meshio import load_mesh  # pymeshlab: imported only when a file gets this far

    try:
        constraint_set = constraints.load(path)
        rest_vertices, _ = load_mesh(constraint_set.rest)
        constraints.resolve(constraint_set, rest_vertices)
    except PipelineError as error:  # ConstraintError, or MeshFileError for an unreadable rest mesh
        return [str(error)]
    return []
