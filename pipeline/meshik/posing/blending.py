"""`meshik blend`: combine the example poses with given weights (no handles) and save the mesh."""
import os
from pathlib import Path
from typing import Optional, Sequence

import numpy as np

from meshik.errors import OutputError, PipelineError


def blend_to_file(inputs: Sequence, weights: Sequence[float], out, feature_space: Optional[str] = None) -> np.ndarray:
    """Blend and write `out` (.drc, or any format pymeshlab writes); returns the #V by 3 positions.

    inputs: [constraint file] (its rest mesh, examples and feature space) or [rest mesh, example, ...].
    weights: one per example. feature_space overrides the constraint file's (default nonlinear).
    Raises PipelineError (or meshik.InputError from the core) on bad input.
    """
    import meshik
    from meshik.export.draco import animation_grid, encode_frame
    from meshik.inputs.meshio import load_example_set, save_mesh, saveable_format
    from meshik.outputs.staging import check_not_inputs, check_writable

    inputs = [Path(p) for p in inputs]
    if len(inputs) == 1 and inputs[0].suffix.lower() == ".json":
        from meshik.inputs.constraints import load

        constraint_set = load(inputs[0])
        rest, examples = constraint_set.rest, constraint_set.examples
        feature_space = feature_space or constraint_set.feature_space
    elif len(inputs) >= 2:
        rest, examples = inputs[0], inputs[1:]
    else:
        raise PipelineError("blend needs a constraint file, or the rest mesh followed by at least one example")
    if len(weights) != len(examples):
        raise PipelineError(f"{len(weights)} weights given for {len(examples)} examples: give one weight per example")
    out = Path(out)
    extension = out.suffix.lower().lstrip(".")
    if extension != "drc" and not (extension.isalnum() and saveable_format(extension)):
        raise OutputError(f"{out}: unknown output format {out.suffix or '(no extension)'!r}: use .drc or a mesh format "
                          "pymeshlab writes (.ply, .obj, .off, .stl, ...)")
    check_writable(out.parent)
    check_not_inputs(out.parent, [out.name], [*inputs, rest, *examples])
    meshes = load_example_set(rest, examples)
    example_set = meshik.ExampleSet(meshes.rest, meshes.faces, list(meshes.examples))
    try:
        vertices = np.asarray(example_set.blend(np.asarray(weights, dtype=float), feature_space=feature_space or "nonlinear"))
    except meshik.InputError as error:
        raise PipelineError(f"weights {', '.join(map(str, weights))}: {error}") from None
    if extension == "drc":
        data = encode_frame(vertices, meshes.faces, np.arange(len(vertices)), animation_grid(vertices))
        write = lambda temporary: temporary.write_bytes(data)  # noqa: E731
    else:
        write = lambda temporary: save_mesh(temporary, vertices, meshes.faces)  # noqa: E731
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        _write_atomically(out, write)
    except OSError as error:
        raise OutputError(f"{out}: cannot write: {error.strerror or error}") from None
    return vertices


def _write_atomically(path: Path, write) -> None:
    """Call write(temporary path with the same extension), then rename it to `path`."""
    temporary = path.with_name(f".{path.stem}.partial-{os.getpid()}{path.suffix}")
    try:
        write(temporary)
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)
