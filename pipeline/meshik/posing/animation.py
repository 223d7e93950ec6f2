"""Pose every frame of an animation with the core: one factorisation, warm-started weights."""
import time
from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional, Sequence

import numpy as np

from meshik.errors import PipelineError
from meshik.inputs.meshio import ExampleMeshes


@dataclass(frozen=True)
class PosedAnimation:
    """The solver's output for every frame.

    vertices: #frames by #V by 3; weights: #frames by #regions #E; iterations, residuals, converged,
    inverted_triangles (how many faces the pose turns over against their blended deformation),
    solve_seconds: #frames each; precompute_seconds: example-set features plus the factorisation.
    """
    vertices: np.ndarray
    weights: np.ndarray
    iterations: np.ndarray
    residuals: np.ndarray
    converged: np.ndarray
    inverted_triangles: np.ndarray
    solve_seconds: np.ndarray
    precompute_seconds: float


def pose_animation(meshes: ExampleMeshes, handles: np.ndarray, targets: np.ndarray, solver_options: Dict[str, Any],
                   on_frame: Optional[Callable[[], None]] = None, context: str = "",
                   features: Optional[Callable[[Optional[int]], Any]] = None,
                   frame_labels: Optional[Sequence[str]] = None, threads: Optional[int] = None) -> PosedAnimation:
    """Solve every frame for one handle set: the system is factored once, each frame starts from
    the previous frame's weights.

    handles: #H vertex indices; targets: #frames by #H by 3; solver_options: keyword arguments of
    meshik.Solver (feature_space, blend, regions, weight_regularization, ...); on_frame: called
    after each frame; context: prefix for error messages about the meshes (e.g. the rest mesh's file);
    features(threads): returns the meshes' meshik.ExampleSet (e.g. kept by an ExampleSetCache); by
    default it is built here; frame_labels: #frames prefixes for a frame's errors (default "frame
    <index>"); threads: for the example-set precompute and each frame's solve (None: all cores).
    Raises PipelineError when the core rejects the input or a frame's pose (e.g. targets so far out
    that the pose overflows), naming the frame.
    """
    import meshik

    start = time.perf_counter()
    try:
        example_set = features(threads) if features is not None else \
            meshik.ExampleSet(meshes.rest, meshes.faces, list(meshes.examples), threads=threads)
        solver = meshik.Solver.from_example_set(example_set, np.asarray(handles, dtype=np.int64), threads=threads,
                                                 **solver_options)
    except meshik.InputError as error:
        raise PipelineError(f"{context}: {error}" if context else str(error)) from None
    precompute = time.perf_counter() - start
    frames, count = len(targets), len(meshes.rest)
    vertices = np.empty((frames, count, 3))
    weights = np.empty((frames, solver.num_weights))
    iterations, residuals = np.empty(frames, dtype=np.int64), np.empty(frames)
    converged, seconds = np.empty(frames, dtype=bool), np.empty(frames)
    inverted = np.empty(frames, dtype=np.int64)
    previous = None
    for k in range(frames):
        start = time.perf_counter()
        try:
            result = solver.solve(targets[k], initial_weights=previous)
        except meshik.InputError as error:
            label = frame_labels[k] if frame_labels is not None else f"frame {k}"
            raise PipelineError(f"{label}: {error}") from None
        seconds[k] = time.perf_counter() - start
        vertices[k], weights[k] = result.vertices, result.weights
        iterations[k], residuals[k], converged[k] = result.iterations, result.residual, result.converged
        inverted[k] = len(result.inverted_triangles)
        previous = weights[k]
        if on_frame is not None:
            on_frame()
    return PosedAnimation(vertices=vertices, weights=weights, iterations=iterations, residuals=residuals,
                          converged=converged, inverted_triangles=inverted, solve_seconds=seconds,
                          precompute_seconds=precompute)
