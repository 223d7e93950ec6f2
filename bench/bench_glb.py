"""Animated .glb sizes on the 48-frame horse gallop (run by `make bench` with --samples DIR --data DIR).

The gallop tracked by MeshIK (bench_pipeline's constraint file) is written as each .glb variant:
draco (Draco base mesh, one float32 morph target per frame: the file before meshopt), quantized
(KHR_mesh_quantization, the default) and meshopt (quantized + EXT_meshopt_compression, opt-in),
14 position bits (the default; meshopt also at 12); each quantized variant with the low-rank morph
basis (--glb-targets basis, the default) and with one target per frame (frames).
Morph targets, bytes, gzip -9 bytes, each file's largest position error against the solver's
frames (report.json, a fraction of the animation's bounding-box diagonal) and the range of its
morph weights (inside [0, 1]: Blender clamps its shape-key sliders there); the meshopt files against
the Draco one: <= 1/4 of its bytes, and gzipped <= 1/10 of them.
"""
import gzip
import pathlib
import sys
import tempfile

# (row label, glb variant, position bits, glb targets): 12 bits shows what a coarser grid buys
VARIANTS = (("draco", "draco", 14, "frames"), ("quantized", "quantized", 14, "basis"),
            ("quantized per frame", "quantized", 14, "frames"), ("meshopt", "meshopt", 14, "basis"),
            ("meshopt per frame", "meshopt", 14, "frames"), ("meshopt 12 bits", "meshopt", 12, "basis"))


def main() -> int:
    """The table; exit status 1 when the default meshopt file misses 1/4 of the Draco file's bytes or,
    gzipped, 1/10 of them."""
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from bench_pipeline import gallop_constraints, gallop_data
    from meshik.export.glb_reader import read_animation_glb
    from meshik.pipeline import pose_job

    folders = gallop_data(__doc__, "bench_glb")
    if folders is None:
        return 0
    horse, gallop = folders

    with tempfile.TemporaryDirectory(prefix="meshik-bench-") as scratch:
        path = gallop_constraints(horse, gallop, pathlib.Path(scratch))
        rows, drc = {}, None
        for label, variant, bits, targets in VARIANTS:
            out = pathlib.Path(scratch) / label.replace(" ", "_")
            report = pose_job(path, out, formats=("drc", "glb"), glb=variant, position_bits=bits, glb_targets=targets,
                              quiet=True, force=True)
            entry = report["compressed_outputs"]["gallop.glb"]
            data = (out / "gallop.glb").read_bytes()
            weights = read_animation_glb(data).weights
            rows[label] = (entry["morph_targets"], entry["bytes"], len(gzip.compress(data, 9)),
                           entry["max_position_error"], f"{weights.min():.2f}..{weights.max():.2f}")
            drc = report["compressed_outputs"]["frames/*.drc"]
    print(f"horse gallop tracked by MeshIK: {drc['files']} frames, .drc and .glb position grids 14 bits unless said")
    print(f"{'output':<26}{'targets':>8}{'bytes':>12}{'gzip -9':>12}{'vs draco glb':>14}{'max position error':>20}"
          f"{'weights':>12}")
    draco_bytes = rows["draco"][1]
    for variant, (targets, size, zipped, error, weights) in rows.items():
        print(f"  {variant + ' .glb':<24}{targets:>8}{size:>12,}{zipped:>12,}{size / draco_bytes:>14.3f}{error:>19.2e}"
              f"{weights:>12}")
    print(f"  {'.drc frames (all)':<24}{'':>8}{drc['bytes']:>12,}{'':>12}{drc['bytes'] / draco_bytes:>14.3f}"
          f"{drc['max_position_error']:>19.2e}")
    verdicts = {}
    for label in ("meshopt", "meshopt per frame"):  # 14 bits; the first is meshopt's default targets
        _, size, zipped, _, _ = rows[label]
        small, zipped_small = size <= draco_bytes / 4, zipped <= draco_bytes / 10
        verdicts[label] = small and zipped_small
        print(f"{label} .glb: {draco_bytes / size:.2f}x smaller than the draco .glb (goal >= 4) "
              f"[{'PASS' if small else 'FAIL'}]; gzipped {draco_bytes / zipped:.2f}x (goal >= 10) "
              f"[{'PASS' if zipped_small else 'FAIL'}]")
    return 0 if verdicts["meshopt"] else 1


if __name__ == "__main__":
    sys.exit(main())
