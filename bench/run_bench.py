"""`make bench`: runs every C++ benchmark (build/bench/bench_*) and every Python benchmark
(bench/bench_*.py) in turn, each printing its own table. Results also go to bench_output/.

Each C++ benchmark takes: --samples DIR (sample_meshes/) and --data DIR (../shared/data, may be
absent). Each Python benchmark is run as a script with the same arguments. They run with
OMP_WAIT_POLICY=PASSIVE unless it is set, as `import meshik` sets it (waiting threads sleep).
"""
import argparse
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--build", default=str(ROOT / "build"), help="CMake build folder")
    parser.add_argument("--only", default="", help="run only benchmarks whose name contains this")
    args = parser.parse_args()
    common = ["--samples", str(ROOT / "sample_meshes"), "--data", str(ROOT.parent / "shared" / "data")]
    out_dir = ROOT / "bench_output"
    out_dir.mkdir(exist_ok=True)
    commands = [[str(p)] for p in sorted((pathlib.Path(args.build) / "bench").glob("bench_*")) if p.is_file() and p.stat().st_mode & 0o111]
    commands += [[sys.executable, str(p)] for p in sorted((ROOT / "bench").glob("bench_*.py"))]
    env = {**os.environ, "OMP_WAIT_POLICY": os.environ.get("OMP_WAIT_POLICY", "PASSIVE")}
    failed = 0
    for command in commands:
        name = pathlib.Path(command[-1]).stem
        if args.only and args.only not in name:
            continue
        print(f"\n=== {name} ===", flush=True)
        proc = subprocess.run(command + common, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              env=env)
        sys.stdout.write(proc.stdout)
        (out_dir / f"{name}.txt").write_text(proc.stdout)
        if proc.returncode != 0:
            print(f"{name}: exit status {proc.returncode}")
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
