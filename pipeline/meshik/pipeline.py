"""One job: constraint file -> example set -> pose every frame (-> simplify) -> compressed outputs.

    report = pose_job("shot.json", "out/shot", simplify=2000, formats=("drc", "glb", "ply"))

Outputs in the job folder: frames/<frame>.drc (Draco, edgebreaker, one quantisation grid, the
"original_id" attribute), <job>.glb (morph targets + animation, weights in [0, 1]; glb="quantized",
the default: positions and deltas quantized on one position_bits grid, read by every reader tested;
"meshopt": the same with EXT_meshopt_compression, which Blender 5.0.1 refuses; both with a
low-rank morph basis (glb_targets="basis") or one target per frame ("frames");
"draco": a Draco base mesh and one float32 target per frame),
frames/<frame>.<ext> for any format pymeshlab writes, vertex_ids.txt (original vertex id of each
output vertex, when simplified), and report.json (written last). A simplified job poses at full
resolution and simplifies every posed frame as it simplified the example set (simplify_first=True:
poses the simplified example set instead, faster but it may move differently). Nothing is created when the
input is bad; an interrupted job leaves no file under its final name; a job whose outputs are
complete for the same inputs and options is skipped.
"""
import dataclasses
import hashlib
import json
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, TextIO, Tuple, Union

import numpy as np

from meshik.inputs import constraints as constraint_files
from meshik.errors import PipelineError
from meshik.export.draco import DEFAULT_QUANTIZATION_BITS, animation_grid, encode_frame
from meshik.export.glb_draco import animation_glb
from meshik.export.glb_layout import glb_size_problem
from meshik.export.glb_quantized import GLB_TARGETS, MAX_POSITION_BITS, quantized_animation_glb
from meshik.export.output_errors import OutputErrors
from meshik.inputs.meshio import load_example_set, save_mesh, saveable_format
from meshik.posing.animation import PosedAnimation, pose_animation
from meshik.progress_bars import stage_progress
from meshik.terminal_text import one_line
from meshik.posing.simplify import SIMPLIFIERS, SimplifiedMeshes, remap_handles, simplify as simplify_meshes, simplify_animation
from meshik.outputs.staging import REPORT_NAME, StagedOutput, check_not_inputs, check_writable, is_complete, read_report

# 3: the fast simplifier became MeshIK's own decimator (other meshes; no "snapped_vertices"): redo older jobs
REPORT_VERSION = 3
DEFAULT_FORMATS = ("drc", "glb")
GLB_VARIANTS = ("quantized", "meshopt", "draco")
DEFAULT_POSITION_BITS = 14
GENERATOR = "MeshIK pipeline"


def pose_job(constraints_path, out_dir, simplify: Optional[Union[int, float]] = None, simplifier: str = "fast",
             formats: Sequence[str] = DEFAULT_FORMATS, feature_space: Optional[str] = None, quiet: bool = False,
             quantization_bits: int = DEFAULT_QUANTIZATION_BITS, force: bool = False,
             stream: Optional[TextIO] = None, example_cache=None, threads: Optional[int] = None,
             glb: str = "quantized", position_bits: int = DEFAULT_POSITION_BITS,
             glb_targets: str = "basis", within=None, simplify_first: bool = False, blend: Optional[str] = None,
             regions: Union[None, int, str] = None, handle_stiffness: Optional[float] = None,
             solver_defaults: Optional[Dict[str, Any]] = None) -> Dict[str, Any]:
    """Run one job and return its report (also written as out_dir/report.json).

    simplify: target triangle count (int), or the fraction of triangles to keep (float in (0, 1)),
              or None for full resolution; simplifier: "fast" or "openmesh"; by default every frame is
              posed at full resolution, then simplified as the example set was (the simplified animation
              is the simplification of the full one); simplify_first: pose the simplified example set
              instead (faster per frame, but its weights, and so its motion, may differ);
    formats: "drc", "glb" and/or extensions pymeshlab writes ("ply", "obj", ...);
    feature_space: overrides the constraint file's ("nonlinear" or "linear");
    blend / regions / handle_stiffness: override the file's ("affine" or "free"; a region count or "auto";
                                        a number >= 0, 0 = hard handles);
    solver_defaults: "blend", "regions" and / or "handle_stiffness" as above, for a file that does not set
                     them (a batch's --blend / --regions / --handle-stiffness);
    force: run even when out_dir already holds the complete outputs of the same job;
    example_cache: an ExampleSetCache (meshik.posing.example_cache) to take the meshes and features from;
    threads: for the example-set precompute, the solves and the fast simplifier (None: all cores; the
             outputs are the same for any count);
    glb: the .glb variant ("quantized", "meshopt" or "draco"; meshik.export.glb_readers says who reads each); position_bits: the grid of the
    meshopt and quantized .glb (1..15; the .drc frames and the Draco .glb use quantization_bits);
    glb_targets: their morph targets, "basis" (fewest within the grid's rounding) or "frames" (one per frame);
    within: a folder that contains out_dir and that the run owns as a whole (a batch's --out): out_dir
            is then replaced in one folder swap (meshik.outputs.staging).
    The returned report has "skipped": True when the job was already complete.
    Raises PipelineError (ConstraintError, MeshFileError, OutputError) or meshik.InputError.
    """
    clock = _Clock()
    constraints_path, out_dir = Path(constraints_path), Path(out_dir)
    constraint_set = constraint_files.load(constraints_path)
    formats = parse_formats(formats)
    _check_choice("simplifier", simplifier, SIMPLIFIERS)
    _check_choice("feature space", feature_space, constraint_files.FEATURE_SPACES + (None,))
    if not 1 <= quantization_bits <= 30:
        raise PipelineError(f"quantization bits must be between 1 and 30, got {quantization_bits}")
    _check_choice("glb variant", glb, GLB_VARIANTS)
    _check_choice("glb targets", glb_targets, GLB_TARGETS)
    if not 1 <= position_bits <= MAX_POSITION_BITS:
        raise PipelineError(f"position bits must be between 1 and {MAX_POSITION_BITS}, got {position_bits}")
    check_writable(out_dir)
    _check_choice("blend", blend, constraint_files.BLENDS + (None,))
    defaults = dict(solver_defaults or {})
    unknown = sorted(set(defaults) - {"blend", "regions", "handle_stiffness"})
    if unknown:
        raise PipelineError(f"solver defaults may set blend, regions and handle_stiffness only, got {', '.join(unknown)}")
    _check_choice("default blend", defaults.get("blend"), constraint_files.BLENDS + (None,))
    solver_options = dict({"feature_space": "nonlinear"}, **defaults)
    solver_options.update(constraint_set.solver_options())
    if feature_space:
        solver_options["feature_space"] = feature_space
    for name, value in (("blend", blend), ("regions", regions), ("handle_stiffness", handle_stiffness)):
        if value is not None:
            solver_options[name] = value
    key = job_key(constraint_set, solver_options, simplify, simplifier, formats, quantization_bits,
                  (glb, position_bits, glb_targets) if "glb" in formats else None, simplify_first)
    if not force and is_complete(out_dir, key):
        return dict(read_report(out_dir), skipped=True)

    name = constraints_path.stem
    say = _Announcer(name, quiet, stream)
    meshes, features = example_cache.get(constraint_set.rest, constraint_set.examples) if example_cache is not None \
        else (load_example_set(constraint_set.rest, constraint_set.examples), None)
    resolved = constraint_files.resolve(constraint_set, meshes.rest)
    clock.lap("load")
    say(f"{len(meshes.rest)} vertices, {len(meshes.faces)} triangles, {len(meshes.examples)} examples, "
        f"{len(resolved.handles)} handle vertices, {len(resolved.frame_names)} frames")

    target = _target_triangles(simplify, len(meshes.faces)) if simplify is not None else None
    simplified = simplify_meshes(meshes, target, resolved.handles, simplifier, threads) \
        if target is not None and simplify_first else None
    pose_meshes = simplified.meshes if simplified is not None else meshes
    if target is None or simplify_first:  # else known once the frames are simplified
        _check_glb_size(constraints_path, formats, len(resolved.frame_names), pose_meshes.rest)
    clock.lap("simplify")
    handles, kept = remap_handles(simplified, resolved.handles)
    inputs = (constraints_path, meshes.rest_path, *meshes.example_paths)
    check_not_inputs(out_dir, _output_names(name, formats, resolved.frame_names, target is not None), inputs)

    pose_ids = simplified.source_vertex if simplified is not None else np.arange(len(meshes.rest))
    with stage_progress(f"{name}: posing", len(resolved.frame_names), quiet, stream) as advance:
        posed = pose_animation(pose_meshes, handles, resolved.targets[:, kept],
                               _mesh_solver_options(solver_options, pose_ids, len(meshes.rest), constraints_path),
                               on_frame=advance,
                               context=str(constraint_set.rest), features=features if simplified is None else None,
                               threads=threads,
                               frame_labels=[f"{constraints_path}: frame {f}" for f in resolved.frame_names])
    clock.lap("pose")
    if target is not None and not simplify_first:
        simplified, frames = simplify_animation(meshes, posed.vertices, target, resolved.handles, simplifier, threads)
        posed = dataclasses.replace(posed, vertices=frames)
        handles, kept = remap_handles(simplified, resolved.handles)
        _check_glb_size(constraints_path, formats, len(resolved.frame_names), simplified.meshes.rest)
        clock.lap("simplify_frames")
    if simplified is not None:
        say(f"simplified ({simplifier}) to {len(simplified.meshes.rest)} vertices, {len(simplified.meshes.faces)} triangles")
    posed_meshes = simplified.meshes if simplified is not None else meshes
    vertex_ids = simplified.source_vertex if simplified is not None else np.arange(len(meshes.rest))
    everything = np.concatenate([posed.vertices, posed_meshes.rest[None]])
    grid = animation_grid(everything, quantization_bits)
    glb_grid = grid if glb == "draco" else animation_grid(everything, position_bits)
    grids = ([(grid, "--quantization-bits")] if {"drc", "glb"} & set(formats) else []) \
        + ([(glb_grid, "--position-bits")] if "glb" in formats and glb != "draco" else [])
    for checked, option in grids:
        _check_grid_resolution(constraints_path, checked, posed_meshes.rest, posed.vertices, resolved.frame_names,
                               resolved.handles[kept], posed_meshes.rest[handles], resolved.targets[:, kept], option)
    errors = OutputErrors(posed.vertices, vertex_ids)
    writing = stage_progress(f"{name}: writing", _file_count(formats, len(resolved.frame_names)), quiet, stream)
    with StagedOutput(out_dir, within) as staged, writing as advance:
        _export(staged, name, posed_meshes.rest, posed_meshes.faces, posed, resolved.frame_names, vertex_ids,
                simplified is not None, grid, constraint_set.fps, formats, advance, (glb, glb_grid, glb_targets), errors)
        clock.lap("export")
        fit = _handle_fit(posed.vertices, simplified, resolved.handles, resolved.targets)
        report = _report(name, key, constraint_set, meshes, simplified, (simplifier, simplify_first), solver_options,
                         resolved, posed, fit, grid, clock.laps)
        report["compressed_outputs"] = errors.report()
        report = staged.commit(report, inputs=inputs)
    say(f"done: {len(resolved.frame_names)} frames, worst handle fit error {fit.max():.3g}, "
        f"{sum(report['outputs'].values()) / 1e6:.2f} MB in {out_dir}")
    return dict(report, skipped=False)


def _check_glb_size(source: Path, formats: Tuple[str, ...], frames: int, vertices: np.ndarray) -> None:
    """PipelineError when a .glb is asked for and `frames` frames of these #V by 3 vertices cannot be one."""
    too_large = glb_size_problem(frames, len(vertices)) if "glb" in formats else None
    if too_large:
        raise PipelineError(f"{source}: {too_large}: leave glb out of --format or split the animation")


def parse_formats(formats: Union[str, Sequence[str]]) -> Tuple[str, ...]:
    """Output formats as a tuple of lower-case names ("drc", "glb", or a pymeshlab extension).

    Accepts "drc,glb,ply" or a sequence. Raises PipelineError for an empty list or a format
    nothing here can write.
    """
    names = formats.split(",") if isinstance(formats, str) else list(formats)
    parsed = tuple(dict.fromkeys(n.strip().lower().lstrip(".") for n in names if n.strip()))
    if not parsed:
        raise PipelineError("no output format given (e.g. drc,glb,ply)")
    for name in parsed:
        if name not in DEFAULT_FORMATS and not (name.isalnum() and saveable_format(name)):
            raise PipelineError(f"unknown output format {name!r}: use drc, glb or a mesh format pymeshlab writes (ply, obj, off, stl, ...)")
    return parsed


def _mesh_solver_options(solver_options: Dict[str, Any], vertex_ids: np.ndarray, num_vertices: int,
                         source) -> Dict[str, Any]:
    """solver_options for the posed mesh: vertex-group regions (name -> rest vertex indices) become
    meshik.Solver's array of region ids, taken at the posed vertices' rest ids (vertex_ids)."""
    regions = solver_options.get("regions")
    if not isinstance(regions, dict):
        return solver_options
    ids = constraint_files.region_vertex_groups(regions, num_vertices, source)
    return dict(solver_options, regions=ids[np.asarray(vertex_ids)])


def job_key(constraint_set: constraint_files.ConstraintSet, solver_options: Dict[str, Any], simplify, simplifier: str,
            formats: Tuple[str, ...], quantization_bits: int, glb_options=None, simplify_first: bool = False) -> str:
    """A hash of everything a job's outputs depend on: the constraint file's bytes, the size and
    modification time of every mesh file, and the options (glb_options: the .glb's variant and
    position bits and targets, None without a .glb; simplify_first: counts only when simplified)."""
    meshes = [constraint_set.rest, *constraint_set.examples]
    state = {
        "constraints": hashlib.sha256(constraint_set.source.read_bytes()).hexdigest(),
        "meshes": [[str(p), p.stat().st_size, p.stat().st_mtime_ns] for p in meshes],
        "options": [solver_options, simplify, simplifier if simplify is not None else None, list(formats), quantization_bits]
                   + ([list(glb_options)] if glb_options is not None else [])
                   + ([{"simplify_first": simplify_first}] if simplify is not None else []),
        "report_version": REPORT_VERSION,
    }
    return hashlib.sha256(json.dumps(state, sort_keys=True, default=str).encode()).hexdigest()


def _check_choice(what: str, value, choices) -> None:
    """PipelineError unless value is one of choices."""
    if value not in choices:
        listed = ", ".join(str(c) for c in choices if c is not None)
        raise PipelineError(f"unknown {what} {value!r} (choose from: {listed})")


def _target_triangles(simplify: Union[int, float], triangles: int) -> int:
    """Target triangle count from an int count or a float fraction in (0, 1); PipelineError otherwise."""
    if isinstance(simplify, bool) or not isinstance(simplify, (int, float)):
        raise PipelineError(f"--simplify expects a triangle count or a fraction, got {simplify!r}")
    if isinstance(simplify, float) and not simplify.is_integer():
        if not 0.0 < simplify < 1.0:
            raise PipelineError(f"--simplify fraction must be between 0 and 1, got {simplify}")
        return max(4, int(round(simplify * triangles)))
    return int(simplify)


def _export(staged: StagedOutput, name: str, rest: np.ndarray, faces: np.ndarray, posed: PosedAnimation,
            frame_names: Sequence[str], vertex_ids: np.ndarray, simplified: bool, grid, fps: float,
            formats: Tuple[str, ...], advance: Callable[[], None], glb_choice: Tuple[str, Any, str],
            errors: OutputErrors) -> None:
    """Write every requested format into the staging folder; advance() after each file.
    glb_choice: (variant, grid, targets) of the .glb; errors: records the bytes and position error of the
    .drc frames and the .glb."""
    for fmt in formats:
        if fmt == "drc":
            for frame, vertices in zip(frame_names, posed.vertices):
                data = encode_frame(vertices, faces, vertex_ids, grid)
                staged.write(f"frames/{frame}.drc", data)
                errors.add_drc_frame(data)
                advance()
        elif fmt == "glb":
            variant, glb_grid, targets = glb_choice
            if variant == "draco":
                data = animation_glb(rest, faces, posed.vertices, frame_names, vertex_ids, grid, fps, name, GENERATOR)
            else:
                data = quantized_animation_glb(rest, faces, posed.vertices, frame_names, vertex_ids, glb_grid, fps, name,
                                               GENERATOR, meshopt=variant == "meshopt", targets=targets)
            staged.write(f"{name}.glb", data)
            errors.add_glb(f"{name}.glb", variant, data, glb_grid)
            advance()
        else:
            for frame, vertices in zip(frame_names, posed.vertices):
                relative = f"frames/{frame}.{fmt}"
                staged.save(relative, lambda path: save_mesh(path, vertices, faces))
                advance()
            if simplified and "vertex_ids.txt" not in staged.files:
                staged.write("vertex_ids.txt", "".join(f"{i}\n" for i in vertex_ids).encode())


def _output_names(name: str, formats: Tuple[str, ...], frame_names: Sequence[str], simplified: bool) -> List[str]:
    """Every file a job writes, relative to its folder (report.json included), as _export names them."""
    names = [REPORT_NAME] + [f"{name}.glb" for fmt in formats if fmt == "glb"]
    names += [f"frames/{frame}.{fmt}" for fmt in formats if fmt != "glb" for frame in frame_names]
    if simplified and any(fmt not in DEFAULT_FORMATS for fmt in formats):
        names.append("vertex_ids.txt")
    return names


def _file_count(formats: Tuple[str, ...], frames: int) -> int:
    """How many files the formats make: one .glb, one file per frame for every other format."""
    return sum(1 if fmt == "glb" else frames for fmt in formats)


def _handle_fit(posed_vertices: np.ndarray, simplified: Optional[SimplifiedMeshes], handles: np.ndarray,
                targets: np.ndarray) -> np.ndarray:
    """#frames by #H distances from each original handle's target to the posed vertex it maps to."""
    rows = simplified.vertex_map[handles] if simplified is not None else handles
    return np.linalg.norm(posed_vertices[:, rows] - targets, axis=2)


# The coarsest shared quantisation step accepted, as a fraction of the rest mesh's bounding-box
# diagonal: beyond it, one far-off frame would blur every frame of the animation.
MAX_GRID_STEP = 0.01


def _check_grid_resolution(source: Path, grid, rest: np.ndarray, frames: np.ndarray, frame_names: Sequence[str],
                           handles: np.ndarray, handle_rest: np.ndarray, targets: np.ndarray,
                           option: str = "--quantization-bits") -> None:
    """PipelineError unless the animation's shared grid resolves the mesh (step <= MAX_GRID_STEP of
    the rest diagonal). rest: #V by 3; frames: #frames by #V by 3; handles: #H vertex ids (as the
    user numbers them); handle_rest: #H by 3 their rest positions; targets: #frames by #H by 3. The message names the frame reaching farthest from the rest mesh and
    its handle whose target lies farthest from that handle's rest position, and the option that sets
    the grid's bits.
    """
    diagonal = float(np.linalg.norm(rest.max(axis=0) - rest.min(axis=0))) or 1.0
    if grid.step <= MAX_GRID_STEP * diagonal:
        return
    centre = (rest.max(axis=0) + rest.min(axis=0)) / 2
    frame = int(np.argmax(np.abs(frames - centre).reshape(len(frames), -1).max(axis=1)))
    handle = int(np.argmax(np.linalg.norm(targets[frame] - handle_rest, axis=1))) if len(handles) else 0
    where = f"frame {frame_names[frame]}, handle vertex {int(handles[handle])}" if len(handles) else f"frame {frame_names[frame]}"
    raise PipelineError(f"{source}: {where}: the animation spans {grid.range / diagonal:.3g} times the rest mesh's size, "
                        f"so its shared {grid.bits}-bit grid would blur every frame by {grid.step / diagonal:.2g} of the "
                        f"mesh's diagonal: move that frame's targets closer or raise {option}")


def _finite_or_none(value: Optional[float]) -> Optional[float]:
    """The value as a float when given and finite, else None (JSON has no infinity)."""
    return None if value is None or not np.isfinite(value) else float(value)


def _report(name, key, constraint_set, meshes, simplified, simplification: Tuple[str, bool], solver_options, resolved,
            posed: PosedAnimation, fit: np.ndarray, grid, timings: Dict[str, float]) -> Dict[str, Any]:
    """The report.json document (without "outputs", which the commit adds); simplification: (simplifier,
    simplify_first)."""
    simplifier, simplify_first = simplification
    frames = [{"name": frame, "weights": posed.weights[k].tolist(), "iterations": int(posed.iterations[k]),
               "residual": float(posed.residuals[k]), "converged": bool(posed.converged[k]),
               "inverted_triangles": int(posed.inverted_triangles[k]),
               "solve_seconds": float(posed.solve_seconds[k]),
               "handle_fit_error": {"max": float(fit[k].max()), "rms": float(np.sqrt(np.mean(fit[k] ** 2)))}}
              for k, frame in enumerate(resolved.frame_names)]
    posed_count = len(simplified.meshes.rest) if simplified is not None and simplify_first else len(meshes.rest)
    return {
        "report_version": REPORT_VERSION,
        "job": name,
        "job_key": key,
        "constraints": str(constraint_set.source),
        "input": {"rest": str(meshes.rest_path), "examples": [str(p) for p in meshes.example_paths],
                  "vertices": len(meshes.rest), "triangles": len(meshes.faces)},
        "simplification": None if simplified is None else {
            "simplifier": simplifier, "posed": "simplified example set" if simplify_first else "full resolution",
            "vertices": len(simplified.meshes.rest), "triangles": len(simplified.meshes.faces),
            "distance_bound": _finite_or_none(simplified.distance_bound), "bound_relaxations": simplified.relaxations,
            "merged_handle_vertices": int(len(resolved.handles) - len(np.unique(simplified.vertex_map[resolved.handles])))},
        "solver": dict(solver_options, handle_vertices=len(resolved.handles), posed_vertices=posed_count),
        "frame_count": len(frames),
        "fps": constraint_set.fps,
        "handle_fit_error": {"max": float(fit.max()), "rms": float(np.sqrt(np.mean(fit ** 2)))},
        "inverted_triangles": {"max": int(posed.inverted_triangles.max()),
                               "frames": int(np.count_nonzero(posed.inverted_triangles))},
        "quantization": {"bits": grid.bits, "origin": list(grid.origin), "range": grid.range, "step": grid.step},
        "timings": dict(timings, precompute=posed.precompute_seconds, solve_total=float(posed.solve_seconds.sum()),
                        solve_mean=float(posed.solve_seconds.mean())),
        "frames": frames,
    }


class _Clock:
    """Wall-clock laps of a job: lap(name) records the seconds since the previous lap."""

    def __init__(self):
        self.start = self.last = time.perf_counter()
        self.laps: Dict[str, float] = {}

    def lap(self, name: str) -> None:
        """Record the time since the previous lap under `name` (and the running total)."""
        now = time.perf_counter()
        self.laps[name] = now - self.last
        self.laps["total"] = now - self.start
        self.last = now


class _Announcer:
    """Prints "<job>: message" lines on stderr unless quiet."""

    def __init__(self, name: str, quiet: bool, stream: Optional[TextIO]):
        self.name, self.quiet, self.stream = name, quiet, stream

    def __call__(self, message: str) -> None:
        """Print one line for this job (nothing when quiet)."""
        if not self.quiet:
            print(one_line(f"{self.name}: {message}"), file=self.stream or sys.stderr, flush=True)
