"""`make demo`: poses the shipped sample sets through their constraint-file animations with the
batch pipeline (simplify, pose, compress), prints a summary table and writes, per sample, a PNG
contact sheet rendered from the decoded Draco frames, and index.html, a page that plays every .glb
(served by `meshik view demo_output`), so a person can look at the result.

Usage: python -m meshik.demo [--out demo_output] [--samples sample_meshes]
"""
import argparse
import json
import sys
from pathlib import Path
from typing import Any, Dict, List

import numpy as np

from meshik.preview.contact_sheet import contact_sheet
from meshik.export.draco import decode
from meshik.pipeline import pose_job
from meshik.preview.site import write_viewer

ROOT = Path(__file__).resolve().parents[2]
# (sample, pose_job options): the limb's animation is simplified, the small sets are posed as they are.
DEMO_JOBS = [
    ("limb", {"simplify": 0.5, "simplifier": "fast"}),
    ("flag", {}),
    ("bar", {}),
]


def decoded_frames(job_dir: Path, report: Dict[str, Any]):
    """(#frames by #V by 3 positions, #F by 3 faces) decoded from the job's .drc files, in frame order."""
    meshes = [decode((job_dir / "frames" / f"{frame['name']}.drc").read_bytes()) for frame in report["frames"]]
    return np.stack([m.vertices for m in meshes]), meshes[0].faces


def summary_row(sample: str, report: Dict[str, Any]) -> List[str]:
    """One row of the summary table for a finished job's report."""
    outputs = report["outputs"]
    drc = sum(size for name, size in outputs.items() if name.endswith(".drc"))
    glb = sum(size for name, size in outputs.items() if name.endswith(".glb"))
    solver = report["solver"]
    return [sample, f"{solver['posed_vertices']:,}", str(report["frame_count"]),
            f"{1000 * report['timings']['solve_mean']:.2f}", f"{drc / 1024:.1f}", f"{glb / 1024:.1f}",
            f"{report['handle_fit_error']['max']:.2e}", str(report["inverted_triangles"]["max"])]


def print_table(rows: List[List[str]]) -> None:
    """Prints rows under the summary header, columns aligned."""
    header = ["sample", "vertices", "frames", "ms/frame", "drc KiB", "glb KiB", "max handle error", "max inverted"]
    widths = [max(len(r[i]) for r in [header] + rows) for i in range(len(header))]
    for row in [header, ["-" * w for w in widths]] + rows:
        print("  ".join(cell.rjust(w) for cell, w in zip(row, widths)))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="demo_output", help="output folder (one sub-folder per sample)")
    parser.add_argument("--samples", default=str(ROOT / "sample_meshes"), help="folder of sample sets")
    args = parser.parse_args(argv)
    out, samples = Path(args.out), Path(args.samples)
    rows = []
    for sample, options in DEMO_JOBS:
        job_dir = out / sample
        report = pose_job(samples / sample / "animation.json", job_dir, formats=("drc", "glb"), **options)
        report = json.loads((job_dir / "report.json").read_text())  # the file a user reads
        frames, faces = decoded_frames(job_dir, report)
        sheet = contact_sheet(list(frames), faces, [f["name"] for f in report["frames"]], columns=8, tile=160)
        sheet.save(out / f"{sample}_contact_sheet.png")
        rows.append(summary_row(sample, report))
    print()
    print_table(rows)
    page = write_viewer(out)
    print(f"\noutputs and contact sheets in {out}/ (per sample: frames/*.drc, *.glb, report.json)")
    print(f"preview page: {page} (serve it with: meshik view {out})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
