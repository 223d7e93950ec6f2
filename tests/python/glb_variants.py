"""Every .glb variant written for the reader tests (test_glb_blender, test_glb_babylon): the bar
sample through `pose_job`, full resolution and simplified, as (--glb, --glb-targets) quantized /
meshopt x basis / frames and draco; and the horse gallop (real data, when ../shared/data holds it)
posed once, written as quantized basis (the default), quantized frames and draco."""
import json
import pathlib
from dataclasses import dataclass
from typing import Dict

import numpy as np
import pytest

from conftest import SHARED_DATA, example_set_files
from meshik.export.draco import animation_grid
from meshik.export.glb_container import glb_bytes, split_glb
from meshik.export.glb_draco import animation_glb
from meshik.export.glb_quantized import quantized_animation_glb
from meshik.export.glb_readers import readers_of
from meshik.inputs.meshio import load_mesh
from meshik.pipeline import pose_job

# label: (--glb, --glb-targets); draco has one target per frame whatever --glb-targets says
VARIANTS = {"quantized basis": ("quantized", "basis"), "quantized frames": ("quantized", "frames"),
            "meshopt basis": ("meshopt", "basis"), "meshopt frames": ("meshopt", "frames"), "draco": ("draco", "frames")}


@dataclass(frozen=True)
class GlbCase:
    """One .glb to read: its path, its variant (quantized, meshopt, draco), the solver's frames
    (#frames by #V by 3) and the vertex id of each of their rows (#V, as the file carries them), the
    grid step of the quantized variants (None for draco) and the readers report.json lists for it."""
    glb: pathlib.Path
    variant: str
    frames: np.ndarray
    ids: np.ndarray
    grid_step: object
    readers: dict

    def bound(self) -> float:
        """The documented error bound of the variant: the nearest grid point (quantized, meshopt), float32
        deltas on the Draco base (draco), with a margin for a reader's float32 node transform."""
        if self.grid_step is None:
            return 1e-5 * max(1.0, float(np.ptp(self.frames.reshape(-1, 3), axis=0).max()))
        return self.grid_step * np.sqrt(3) / 2 * 1.01


def solver_frames(folder: pathlib.Path, report: dict) -> np.ndarray:
    """#frames by #V by 3 solver frames of a job written with the ply format, rows = the file's vertex ids."""
    return np.stack([load_mesh(folder / "frames" / f"{frame['name']}.ply")[0] for frame in report["frames"]])


def bar_cases(samples_dir: pathlib.Path, scratch: pathlib.Path) -> Dict[str, GlbCase]:
    """{"<variant label> full|simplified": GlbCase} for the bar sample, full and simplified to 160 triangles."""
    cases = {}
    for resolution, simplify in (("full", None), ("simplified", 160)):
        for label, (variant, targets) in VARIANTS.items():
            folder = scratch / f"bar_{resolution}_{label.replace(' ', '_')}"
            report = pose_job(samples_dir / "bar" / "animation.json", folder, formats=("glb", "ply"), glb=variant,
                              glb_targets=targets, simplify=simplify, quiet=True)
            entry = report["compressed_outputs"]["animation.glb"]
            frames = solver_frames(folder, report)
            ids = np.arange(frames.shape[1]) if simplify is None \
                else np.loadtxt(folder / "vertex_ids.txt", dtype=np.int64).reshape(-1)
            cases[f"{label} {resolution}"] = GlbCase(folder / "animation.glb", variant, frames, ids,
                                                     None if variant == "draco" else entry["grid_step"], entry["readers"])
    return cases


def gallop_cases(shared_data: pathlib.Path, scratch: pathlib.Path) -> Dict[str, GlbCase]:
    """{"<variant label> gallop": GlbCase}: the default .glb of `pose_job` on the tracked gallop, and the
    quantized frames and draco files written from the same frames; {} without the data."""
    from meshik.inputs.tracking import farthest_point_handles, tracking_document

    folder = shared_data / "horse-gallop"
    if not folder.is_dir():
        return {}
    rest_path, example_paths = example_set_files(shared_data / "horse-poses")
    rest, faces = load_mesh(rest_path)
    tracked = {p.stem: load_mesh(p)[0] for p in sorted(folder.glob("*.obj")) if p.stem.isdigit()}
    path = scratch / "gallop.json"
    path.write_text(json.dumps(tracking_document(path, rest_path, example_paths, tracked,
                                                 farthest_point_handles(rest, 12))))
    report = pose_job(path, scratch / "gallop", formats=("glb", "ply"), quiet=True)
    entry = report["compressed_outputs"]["gallop.glb"]
    frames = solver_frames(scratch / "gallop", report)
    names = [frame["name"] for frame in report["frames"]]
    grid = animation_grid(np.concatenate([frames, rest[None]]), entry["position_bits"])
    ids = np.arange(len(rest))
    per_frame = quantized_animation_glb(rest, faces, frames, names, ids, grid, report["fps"], "gallop", "test",
                                        meshopt=False, targets="frames")
    (scratch / "gallop_frames.glb").write_bytes(per_frame)
    (scratch / "gallop_draco.glb").write_bytes(animation_glb(rest, faces, frames, names, ids, grid, report["fps"],
                                                             "gallop", "test"))
    return {"quantized basis gallop": GlbCase(scratch / "gallop" / "gallop.glb", entry["variant"], frames, ids, grid.step,
                                              entry["readers"]),
            "quantized frames gallop": GlbCase(scratch / "gallop_frames.glb", "quantized", frames, ids, grid.step,
                                               readers_of("quantized")),
            "draco gallop": GlbCase(scratch / "gallop_draco.glb", "draco", frames, ids, None, readers_of("draco"))}


def without_animation(glb: pathlib.Path, out: pathlib.Path) -> pathlib.Path:
    """A copy of `glb` with its animations removed (what a reader that ignores them sees); returns out."""
    document, binary = split_glb(glb.read_bytes())
    document.pop("animations")
    out.write_bytes(glb_bytes(document, binary))
    return out


@pytest.fixture(scope="session")
def glb_cases(samples_dir, tmp_path_factory) -> Dict[str, GlbCase]:
    """Every case of bar_cases and gallop_cases, written once for all the reader tests."""
    scratch = tmp_path_factory.mktemp("glb_variants")
    cases = bar_cases(samples_dir, scratch)
    if SHARED_DATA.is_dir():
        cases.update(gallop_cases(SHARED_DATA, scratch))
    return cases


# the labels of glb_cases (the gallop's only when the data is there)
LABELS = [f"{label} {resolution}" for label in VARIANTS for resolution in ("full", "simplified")] \
    + ["quantized basis gallop", "quantized frames gallop", "draco gallop"]
