"""Animated .glb sizes on the 48-frame horse gallop (run by `make bench` with --samples DIR --data DIR).

The gallop tracked by MeshIK (bench_pipeline's constraint file) is written as each .glb variant:
draco (Draco base mesh, float32 morph targets: the file before meshopt), quantized
(KHR_mesh_quantization) and meshopt (quantized + EXT_meshopt_compression), 14 position bits (the
default; meshopt also at 12).
Bytes, gzip -9 bytes and each file's largest position error against the solver's frames (report.json,
a fraction of the animation's bounding-box diagonal); the meshopt file against the Draco one:
<= 1/4 of its bytes, and gzipped <= 1/10 of them.
"""
import gzip
import pathlib
import sys
import tempfile

# (row label, glb variant, position bits): 12 bits shows what a coarser grid buys
VARIANTS = (("draco", "draco", 14), ("quantized", "quantized", 14), ("meshopt", "meshopt", 14),
            ("meshopt 12 bits", "meshopt", 12))


def main() -> int:
    """The table; exit status 1 when the meshopt file misses 1/4 of the Draco file's bytes."""
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from bench_pipeline import gallop_constraints, gallop_data
    from meshik.pipeline import pose_job

    folders = gallop_data(__doc__, "bench_glb")
    if folders is None:
        return 0
    horse, gallop = folders

    with tempfile.TemporaryDirectory(prefix="meshik-bench-") as scratch:
        path = gallop_constraints(horse, gallop, pathlib.Path(scratch))
        rows, drc = {}, None
        for label, variant, bits in VARIANTS:
            out = pathlib.Path(scratch) / label.replace(" ", "_")
            report = pose_job(path, out, formats=("drc", "glb"), glb=variant, position_bits=bits, quiet=True, force=True)
            entry = report["compressed_outputs"]["gallop.glb"]
            rows[label] = (entry["bytes"], len(gzip.compress((out / "gallop.glb").read_bytes(), 9)),
                             entry["max_position_error"])
            drc = report["compressed_outputs"]["frames/*.drc"]
    print(f"horse gallop tracked by MeshIK: {drc['files']} frames, .drc and .glb position grids 14 bits unless said")
    print(f"{'output':<26}{'bytes':>12}{'gzip -9':>12}{'vs draco glb':>14}{'max position error':>20}")
    draco_bytes = rows["draco"][0]
    for variant, (size, zipped, error) in rows.items():
        print(f"  {variant + ' .glb':<24}{size:>12,}{zipped:>12,}{size / draco_bytes:>14.3f}{error:>19.2e}")
    print(f"  {'.drc frames (all)':<24}{drc['bytes']:>12,}{'':>12}{drc['bytes'] / draco_bytes:>14.3f}"
          f"{drc['max_position_error']:>19.2e}")
    size, zipped, _ = rows["meshopt"]  # the default, 14 bits
    quarter, tenth = size <= draco_bytes / 4, zipped <= draco_bytes / 10
    print(f"meshopt .glb: {draco_bytes / size:.2f}x smaller than the draco .glb (goal >= 4) [{'PASS' if quarter else 'FAIL'}]; "
          f"gzipped {draco_bytes / zipped:.2f}x (goal >= 10) [{'PASS' if tenth else 'FAIL'}]")
    return 0 if quarter else 1


if __name__ == "__main__":
    sys.exit(main())
