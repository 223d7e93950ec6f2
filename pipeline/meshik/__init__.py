"""MeshIK: Mesh-Based Inverse Kinematics (Sumner, Zwicker, Gotsman, Popovic 2005).

The solver itself is the C++ extension module ``meshik._core``; this package re-exports it and
adds the batch pipeline in subpackages: inputs (mesh and constraint files), posing, export (Draco,
glTF), outputs (output folders), batch (Dask), preview (`meshik view`); meshik.pipeline.pose_job runs
one job through them, meshik.cli is the `meshik` command. The modules' names before the subpackages
(meshik.meshio, meshik.export_gltf, ...) still import, with a DeprecationWarning (moved_modules).
"""
import os

__version__ = "0.1.0"

# OpenMP threads that wait at a barrier sleep instead of spinning (unless the caller chose a
# policy): a solve's passes meet at several barriers per iteration, and on a machine whose other
# cores are busy a spinning thread takes the time the team's other threads need (measured on the
# 2-core build machine under load: the horse's threaded pose 297 ms spinning against 15-29 ms
# passive). Read by the OpenMP runtime when it loads, i.e. with the core below.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

from meshik._core import Cancelled, ExampleSet, InputError, SolveResult, Solver  # noqa: E402,F401
# The pipeline's own errors (light: the pipeline's modules import pymeshlab, DracoPy, ... lazily).
from meshik.errors import ConstraintError, MeshFileError, OutputError, PipelineError  # noqa: E402,F401
from meshik.moved_modules import install as _install_moved_modules  # noqa: E402

_install_moved_modules()

__all__ = ["Cancelled", "ExampleSet", "InputError", "SolveResult", "Solver",
           "ConstraintError", "MeshFileError", "OutputError", "PipelineError"]
