"""Errors of the batch pipeline: bad input files and unusable output folders.

All derive from ValueError (like the core's meshik.InputError), carry a message that names the
file and the element at fault, and are the only exceptions the loaders raise on bad input.
"""


class PipelineError(ValueError):
    """Bad input or an unusable output location; the message says which file and element."""


class ConstraintError(PipelineError):
    """A constraint file that is malformed or violates the schema; the message names the JSON path."""


class MeshFileError(PipelineError):
    """A mesh file that is missing, unreadable, or inconsistent with the rest of its example set."""


class OutputError(PipelineError):
    """An output folder or file that cannot be written."""
