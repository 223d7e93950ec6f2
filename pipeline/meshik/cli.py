"""The `meshik` command: pose, batch, blend, info, validate, view. Exit status 0 on success, 1 when any job or
file failed (with a message on stderr saying which and why), 2 for a command-line mistake."""
import argparse
import json
import math
import signal
import sys
import threading
from pathlib import Path
from typing import List, Optional

from meshik import __version__


_FORMAT_HELP = ("comma-separated output formats: drc (Draco per frame, edgebreaker, original vertex ids kept), "
                "glb (one glTF: the rest mesh, one morph target per frame and an animation; see --glb), and any mesh "
                "format pymeshlab writes, e.g. ply, obj, off, stl (one file per frame). Default: drc,glb")


def main(argv: Optional[List[str]] = None) -> int:
    """Run the command line `argv` (default sys.argv[1:]); returns the exit status."""
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_request:  # --help (0) or a usage error (2)
        return int(exit_request.code or 0)
    previous_sigterm = _stop_on_sigterm()
    try:
        return args.run(args)
    except ValueError as error:  # PipelineError and the core's InputError: bad input, the message says why
        _print_error(str(error))
        return 1
    except OSError as error:  # a file system failure outside the checked paths: disk full, I/O error
        where = f"{error.filename}: " if error.filename else ""
        _print_error(f"{where}{error.strerror or error}")
        return 1
    except MemoryError:
        _print_error("out of memory (the input is larger than this machine can hold)")
        return 1
    except KeyboardInterrupt:
        print("meshik: interrupted", file=sys.stderr)
        return 130
    finally:
        if previous_sigterm is not None:
            signal.signal(signal.SIGTERM, previous_sigterm)


def _print_error(message: str) -> None:
    """Print `meshik: error: message` on one line of stderr; control characters and file names
    that are not valid UTF-8 are shown as backslash escapes (meshik.terminal_text)."""
    _print_line(f"meshik: error: {message}", sys.stderr)


def _print_line(text: str, stream) -> None:
    """Print `text` as one inert line on `stream` (control characters escaped: one_line)."""
    from meshik.terminal_text import one_line

    print(one_line(text), file=stream, flush=True)


def _stop_on_sigterm():
    """Make SIGTERM stop a run as Ctrl+C does (KeyboardInterrupt: partial outputs are removed).

    Returns the previous handler, or None when not on the main thread (handlers cannot be set there).
    """
    if threading.current_thread() is not threading.main_thread():
        return None

    def interrupt(signum, frame):
        raise KeyboardInterrupt

    return signal.signal(signal.SIGTERM, interrupt)


class _OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors are one line on stderr (escaped as every error line),
    naming the command and pointing at its --help, with exit status 2."""

    def error(self, message: str):
        """Print `<prog>: error: message (see <prog> --help)` and exit with status 2."""
        _print_line(f"{self.prog}: error: {message} (see {self.prog} --help)", sys.stderr)
        self.exit(2)


def _parser() -> argparse.ArgumentParser:
    """The argument parser with its sub-commands."""
    parser = _OneLineParser(
        prog="meshik", description="Mesh-based inverse kinematics: pose a mesh from handle targets within the space "
                                   "of its example poses, and write the animation as compressed assets.")
    parser.add_argument("--version", action="version", version=f"meshik {__version__}")
    commands = parser.add_subparsers(title="commands", metavar="COMMAND", required=True)

    pose = commands.add_parser("pose", help="pose every frame of one constraint file",
                               description="Pose every frame of a constraint file and write the outputs and "
                                           "report.json into DIR. Skips the job when DIR already holds its complete outputs.")
    pose.add_argument("constraints", metavar="CONSTRAINTS", help="constraint file (JSON, format meshik-constraints version 1)")
    _job_options(pose)
    _blend_options(pose, "override the constraint file's {}")
    pose.set_defaults(run=_run_pose)

    batch = commands.add_parser("batch", help="pose many constraint files in parallel on Dask",
                                description="Pose every constraint file as one Dask task, each into DIR/<name of the "
                                            "file>/, on a local cluster of worker processes or on a running Dask "
                                            "scheduler. A failing job does not stop the others; a job whose worker "
                                            "dies is retried; complete jobs are skipped on a re-run. "
                                            "DIR/batch-report.json lists every job.")
    batch.add_argument("constraints", metavar="CONSTRAINTS", nargs="+", help="constraint files")
    batch.add_argument("--jobs", "-j", type=_positive_int, default=None, metavar="N",
                       help="worker processes of the local cluster (default: one per core)")
    batch.add_argument("--memory-limit", default=None, metavar="SIZE",
                       help="memory per local worker, e.g. 4GB; a worker past 95%% of it is restarted and its job "
                            "retried (default auto: the machine's memory shared out; 0: no limit)")
    batch.add_argument("--retries", type=_non_negative_int, default=None, metavar="N",
                       help="times a job whose local worker died is run again before it is reported crashed (default 2)")
    batch.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on this Dask scheduler (e.g. tcp://host:8786) instead of a local cluster; its workers "
                            "must see the input files and DIR at the same paths")
    batch.add_argument("--cache-mb", type=_non_negative_int, default=512, metavar="MB",
                       help="memory per worker for example sets shared by several jobs (default 512; 0: no cache)")
    _job_options(batch)
    _blend_options(batch, "{} for the jobs whose constraint file does not set it")
    batch.set_defaults(run=_run_batch)

    blend = commands.add_parser("blend", help="blend the example poses with given weights (no handles)",
                                description="Combine the examples with the given weights in the chosen feature space "
                                            "and write the mesh.")
    blend.add_argument("inputs", metavar="INPUT", nargs="+",
                       help="a constraint file (uses its rest mesh and examples), or the rest mesh followed by the examples")
    blend.add_argument("--weights", "-w", required=True, type=_float_list, metavar="W1,W2,...",
                       help="one weight per example, comma-separated (0 = rest pose, 1 = that example)")
    blend.add_argument("--out", "-o", required=True, type=Path, metavar="FILE",
                       help="output mesh: .drc or any format pymeshlab writes (.ply, .obj, ...)")
    blend.add_argument("--feature-space", choices=("nonlinear", "linear"), default=None,
                       help="nonlinear (rotations blended in log space; default) or linear (deformation gradients blended linearly)")
    blend.set_defaults(run=_run_blend)

    info = commands.add_parser("info", help="describe meshes, .drc, .glb and constraint files",
                               description="Print counts, bounds and edges of each file; meshes are compared with the "
                                           "first one's triangle list; constraint files are validated.")
    info.add_argument("files", metavar="FILE", nargs="+", help="meshes, .drc, .glb or constraint (.json) files")
    info.add_argument("--json", action="store_true", help="print the summaries as JSON")
    info.set_defaults(run=_run_info)

    view = commands.add_parser("view", help="preview an output folder's animations in a web browser",
                               description="Serve the folder on 127.0.0.1: a page that plays each exported .glb with "
                                           "orbit controls and a frame slider, beside the contact sheet and report "
                                           "(three.js served locally from the pinned npm packages; works offline).")
    view.add_argument("folder", type=Path, metavar="OUT", help="an output folder of pose, batch or the demo")
    view.add_argument("--port", type=_port, default=8000, help="port on 127.0.0.1 (0: any free one; default 8000)")
    view.set_defaults(run=_run_view)

    validate = commands.add_parser("validate", help="check constraint files and print every problem",
                                   description="Check constraint files (format, mesh files, handles on the rest mesh) "
                                               "and print every problem, one per line; exit status 1 when any file has one.")
    validate.add_argument("files", metavar="FILE", nargs="+", help="constraint (.json) files")
    validate.set_defaults(run=_run_validate)
    return parser


def _job_options(parser: argparse.ArgumentParser) -> None:
    """Options shared by `pose` and `batch`."""
    parser.add_argument("--out", "-o", required=True, type=Path, metavar="DIR", help="output folder")
    parser.add_argument("--simplify", type=_simplify_target, metavar="N",
                        help="write a lighter animation of N triangles (an integer) or the fraction of triangles to keep "
                             "(e.g. 0.25): every frame is posed at full resolution, then simplified as the examples were, "
                             "so it moves like the full animation")
    parser.add_argument("--simplify-first", action="store_true",
                        help="with --simplify: pose the simplified examples instead (faster per frame, but the "
                             "simplified mesh may choose other example weights: a limb can move differently)")
    parser.add_argument("--simplifier", choices=("fast", "openmesh"), default="fast",
                        help="the decimator (both lock the handles, sum the error over all poses and bound the "
                             "distance to the full surface in every pose): fast, MeshIK's own; openmesh, OpenMesh's "
                             "decimater, several times slower (default fast)")
    parser.add_argument("--format", dest="formats", default="drc,glb", metavar="LIST", help=_FORMAT_HELP)
    parser.add_argument("--feature-space", choices=("nonlinear", "linear"), default=None,
                        help="override the constraint file's feature space (default: the file's, else nonlinear)")
    parser.add_argument("--quantization-bits", type=_positive_int, default=14, metavar="B",
                        help="Draco position quantisation bits, one grid for the whole animation (default 14)")
    parser.add_argument("--glb", dest="glb", choices=("quantized", "meshopt", "draco"), default="quantized",
                        help="the .glb: quantized (default: KHR_mesh_quantization; opens in Blender, three.js, "
                             "Babylon.js and is fully checked by the Khronos validator), meshopt (opt-in: the same "
                             "compressed with EXT_meshopt_compression, about 1/3 the bytes; needs a meshopt decoder: "
                             "three.js, Babylon.js, glTF-Transform; Blender 5.0.1 refuses it, its importer reads it "
                             "from 5.2) or draco (Draco base mesh, float32 morph targets; Blender, and three.js or "
                             "Babylon.js with a Draco decoder). Morph weights stay in [0, 1] in every variant")
    parser.add_argument("--position-bits", type=_positive_int, default=14, metavar="N",
                        help="bits of the meshopt / quantized .glb's position grid, one grid for the whole animation "
                             "(1 to 15, default 14)")
    parser.add_argument("--glb-targets", dest="glb_targets", choices=("basis", "frames"), default="basis",
                        help="morph targets of the meshopt / quantized .glb: basis (default: the fewest targets, "
                             "mixed by per-frame weights, that keep every frame within the grid's rounding; one per "
                             "frame when no smaller basis does) or frames (one target per frame)")
    parser.add_argument("--force", action="store_true", help="run even when the outputs are already complete")
    parser.add_argument("--threads", type=_thread_count, default=None, metavar="N",
                        help="threads of the example-set precompute, of each solve and of the fast simplifier "
                             "(default: all cores for pose, one per batch worker); the outputs are the same for any count")
    parser.add_argument("--quiet", "-q", action="store_true", help="no progress output (errors are still printed)")


def _blend_options(parser: argparse.ArgumentParser, role: str) -> None:
    """Adds --blend, --regions and --handle-stiffness; role: how they apply, with {} for what each sets (e.g. "override the
    constraint file's {}")."""
    parser.add_argument("--blend", choices=("affine", "free"), default=None,
                        help=role.format("blend of the examples' stretches") + ": affine (tied to the rest pose, "
                             "default) or free (the paper's, the rest pose as one more example)")
    parser.add_argument("--regions", type=_region_count, default=None, metavar="N",
                        help=role.format("regions") + ": spatially varying weights over N regions clustered from "
                             "the examples, or auto (1: one weight vector, the default)")
    parser.add_argument("--handle-stiffness", type=_handle_stiffness, default=None, metavar="S",
                        help=role.format("handle stiffness") + ": 0 = hard handles (met exactly, the default), "
                             "> 0 = soft handles pulled towards their targets")


def _run_pose(args) -> int:
    """`meshik pose`: one job; 0 on success."""
    from meshik.pipeline import pose_job

    report = pose_job(args.constraints, args.out, simplify=args.simplify, simplifier=args.simplifier, formats=args.formats,
                      feature_space=args.feature_space, quiet=args.quiet, quantization_bits=args.quantization_bits,
                      force=args.force, threads=args.threads, glb=args.glb, position_bits=args.position_bits,
                      glb_targets=args.glb_targets, simplify_first=args.simplify_first, blend=args.blend,
                      regions=args.regions, handle_stiffness=args.handle_stiffness)
    if report.get("skipped") and not args.quiet:
        _print_line(f"{args.out}: outputs already complete (use --force to redo)", sys.stderr)
    return 0


def _run_batch(args) -> int:
    """`meshik batch`: every job in parallel; 1 when any failed."""
    from meshik.batch import DEFAULT_RETRIES, run_batch
    from meshik.pipeline import parse_formats

    local_only = [flag for flag, value in (("--jobs", args.jobs), ("--memory-limit", args.memory_limit),
                                           ("--retries", args.retries)) if value is not None]
    if args.scheduler and local_only:
        print(f"meshik batch: error: {', '.join(local_only)} set up the local cluster; with --scheduler the cluster's "
              f"own workers and settings apply", file=sys.stderr)
        return 2
    retries = DEFAULT_RETRIES if args.retries is None else args.retries
    outcomes = run_batch(args.constraints, args.out, jobs=args.jobs, memory_limit=args.memory_limit or "auto",
                         scheduler=args.scheduler, retries=retries, cache_mb=args.cache_mb, quiet=args.quiet,
                         simplify=args.simplify, simplifier=args.simplifier, formats=parse_formats(args.formats),
                         feature_space=args.feature_space, quantization_bits=args.quantization_bits, force=args.force,
                         threads=args.threads, glb=args.glb, position_bits=args.position_bits,
                         glb_targets=args.glb_targets, simplify_first=args.simplify_first,
                         solver_defaults={name: value for name, value in (("blend", args.blend), ("regions", args.regions),
                                                                       ("handle_stiffness", args.handle_stiffness))
                                          if value is not None})
    failed = [o for o in outcomes if o.status in ("failed", "crashed")]
    if failed:
        _print_line(f"meshik: {len(failed)} of {len(outcomes)} jobs failed: {', '.join(o.name for o in failed)}", sys.stderr)
    return 1 if failed else 0


def _run_blend(args) -> int:
    """`meshik blend`: write the blended mesh; 0 on success."""
    from meshik.posing.blending import blend_to_file

    blend_to_file(args.inputs, args.weights, args.out, feature_space=args.feature_space)
    return 0


def _run_info(args) -> int:
    """`meshik info`: one summary per file (text or JSON); 1 when any file could not be read."""
    from meshik.inputs.file_info import describe_files

    summaries, errors = describe_files(args.files)
    if args.json:
        print(json.dumps(summaries, indent=1))
    else:
        for summary in summaries:
            _print_line(summary["file"], sys.stdout)
            for key, value in summary.items():
                if key != "file":
                    _print_line(f"  {key}: {value}", sys.stdout)
    for error in errors:
        _print_error(error)
    return 1 if errors else 0


def _run_validate(args) -> int:
    """`meshik validate`: "<file>: OK" or each problem of each file; 1 when any file has a problem."""
    from meshik.inputs.validation import validate_files

    results = validate_files(args.files)
    for path, problems in zip(args.files, results):
        for line in [f"{path}: OK"] if not problems else problems:
            _print_line(line, sys.stdout)
    return 1 if any(results) else 0


def _run_view(args) -> int:
    """`meshik view`: serve the folder's preview until Ctrl+C; 0 when stopped."""
    from meshik.preview.server import preview_server

    server = preview_server(args.folder, args.port)
    host, port = server.server_address[:2]
    _print_line(f"previewing {args.folder} at http://{host}:{port}/ (Ctrl+C to stop)", sys.stdout)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0


def _positive_int(text: str) -> int:
    """argparse type: an integer >= 1."""
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected an integer >= 1, got {text}")
    return value


def _thread_count(text: str) -> int:
    """argparse type: a thread count from 1 to the core's MAX_THREADS."""
    from meshik._core import MAX_THREADS

    value = _positive_int(text)
    if value > MAX_THREADS:
        raise argparse.ArgumentTypeError(f"expected an integer from 1 to {MAX_THREADS}, got {text}")
    return value


def _port(text: str) -> int:
    """argparse type: a TCP port from 0 (any free one) to 65535."""
    value = _non_negative_int(text)
    if value > 65535:
        raise argparse.ArgumentTypeError(f"expected a port from 0 to 65535, got {text}")
    return value


def _non_negative_int(text: str) -> int:
    """argparse type: an integer >= 0."""
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text}")
    return value


def _region_count(text: str):
    """argparse type for --regions: a count >= 1 or "auto"."""
    if text == "auto":
        return text
    try:
        count = int(text)
    except ValueError:
        count = 0
    if count < 1:
        raise argparse.ArgumentTypeError(f"expected a region count >= 1 or auto, got {text!r}")
    return count


def _handle_stiffness(text: str) -> float:
    """argparse type for --handle-stiffness: a finite number >= 0."""
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not (math.isfinite(value) and value >= 0):
        raise argparse.ArgumentTypeError(f"expected a finite number >= 0, got {text!r}")
    return value


def _simplify_target(text: str):
    """argparse type for --simplify: an integer triangle count, or a fraction in (0, 1)."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a triangle count or a fraction, got {text!r}") from None
    if not 0.0 < value < 1.0:
        raise argparse.ArgumentTypeError(f"a fraction must be between 0 and 1, got {text}")
    return value


def _float_list(text: str) -> List[float]:
    """argparse type: comma-separated finite numbers."""
    try:
        values = [float(part) for part in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}") from None
    if not values or any(v != v or v in (float("inf"), float("-inf")) for v in values):
        raise argparse.ArgumentTypeError(f"expected finite comma-separated numbers, got {text!r}")
    return values
