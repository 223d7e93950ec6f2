"""Reading back a long animation's .glb (issue 23): every buffer view decoded once, against decoding
the view again for every accessor that lies in it (what the reader did before), in the same run.

Every morph target's accessor of a meshopt .glb lies in one shared, compressed buffer view; the
export checks its .glb by reading it back (meshik.export.output_errors), so a per-accessor decode made the
export quadratic in the frames (1,000 frames 2 s, 4,000 14 s, 20,000 not done in 120 s). Prints
one row per frame count: the .glb's size, the read-back with views decoded once and per accessor,
and their ratio. Usage: python bench/bench_glb_readback.py [FRAMES ...] (default 500 1000 2000);
`make bench` also passes --samples and --data, which it does not need.
"""
import argparse
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from meshik.export.glb_container import read_accessor, split_glb, view_reader
from meshik.pipeline import pose_job

ROOT = Path(__file__).resolve().parents[1]


def long_animation_glb(folder: Path, frames: int) -> bytes:
    """The meshopt .glb of the bar sample posed over `frames` frames of distinct targets (one morph
    target per frame: no smaller basis holds them)."""
    shutil.copytree(ROOT / "sample_meshes" / "bar", folder)
    document = json.loads((folder / "animation.json").read_text())
    document["frames"] = [{"targets": {"tip": {"translate": [0.0, 0.3 * np.sin(0.37 * k), 0.2 * np.cos(0.11 * k)]}}}
                          for k in range(frames)]
    (folder / "long.json").write_text(json.dumps(document))
    pose_job(folder / "long.json", folder / "out", formats="glb", glb_targets="frames", quiet=True)
    return (folder / "out" / "long.glb").read_bytes()


def read_targets(data: bytes, decode_once: bool) -> float:
    """Seconds to read every morph target's accessor of the .glb `data` (views decoded once, or
    again for every accessor)."""
    start = time.perf_counter()
    document, binary = split_glb(data)
    cached = view_reader(document, binary)
    view_bytes = cached if decode_once else cached.__wrapped__
    targets = document["meshes"][0]["primitives"][0]["targets"]
    for target in targets:
        read_accessor(document, view_bytes, target["POSITION"])
    return time.perf_counter() - start


def main(argv) -> int:
    """Print the table for the frame counts in argv (default 500 1000 2000); 0."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("frames", type=int, nargs="*", help="frame counts (default 500 1000 2000)")
    parser.add_argument("--samples", help="sample_meshes/ (unused here)")
    parser.add_argument("--data", help="../shared/data (unused here)")
    counts = parser.parse_args(argv).frames or [500, 1000, 2000]
    print(f"{'frames':>7} {'glb bytes':>10} {'decoded once s':>15} {'per accessor s':>15} {'ratio':>7}")
    with tempfile.TemporaryDirectory() as scratch:
        for frames in counts:
            data = long_animation_glb(Path(scratch) / str(frames), frames)
            once = min(read_targets(data, True) for _ in range(3))
            again = read_targets(data, False)
            print(f"{frames:>7} {len(data):>10} {once:>15.3f} {again:>15.3f} {again / once:>7.1f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
