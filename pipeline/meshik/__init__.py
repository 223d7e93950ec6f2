"""MeshIK: Mesh-Based Inverse Kinematics (Sumner, Zwicker, Gotsman, Popovic 2005).

The solver itself is the C++ extension module ``meshik._core``; this package re-exports it and
adds the batch pipeline (constraint files, simplification, posing, compressed export).
"""
from meshik._core import Cancelled, ExampleSet, InputError, SolveResult, Solver  # noqa: F401
# The pipeline's own errors (light: the pipeline's modules import pymeshlab, DracoPy, ... lazily).
from meshik.errors import ConstraintError, MeshFileError, OutputError, PipelineError  # noqa: F401

__all__ = ["Cancelled", "ExampleSet", "InputError", "SolveResult", "Solver",
           "ConstraintError", "MeshFileError", "OutputError", "PipelineError"]
