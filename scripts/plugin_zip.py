"""`make dist`'s plugin archive: dist/meshik-meshlab-plugins-<version>-linux-x86_64.zip holding float/ and
double/ (libfilter_meshik.so, libedit_meshik.so, built by `make plugin`) and INSTALL.md.

Usage: python scripts/plugin_zip.py BUILD_DIR DIST_DIR VERSION; prints the archive's path.
"""
import sys
import zipfile
from pathlib import Path

PLUGINS = ("libfilter_meshik.so", "libedit_meshik.so")


def main(build: Path, dist: Path, version: str) -> Path:
    """Write the archive from build/plugin/{float,double}/ and plugin/INSTALL.md; returns its path.
    Raises SystemExit naming the first missing plugin file."""
    files = {f"{precision}/{name}": build / "plugin" / precision / name
             for precision in ("float", "double") for name in PLUGINS}
    files["INSTALL.md"] = Path(__file__).resolve().parents[1] / "plugin" / "INSTALL.md"
    for path in files.values():
        if not path.is_file():
            raise SystemExit(f"{path}: missing: build the plugins first (make plugin)")
    dist.mkdir(parents=True, exist_ok=True)
    archive = dist / f"meshik-meshlab-plugins-{version}-linux-x86_64.zip"
    partial = archive.with_suffix(".zip.partial")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as out:
        for name, path in files.items():
            out.write(path, f"meshik-meshlab-plugins-{version}/{name}")
    partial.replace(archive)
    return archive


if __name__ == "__main__":
    print(main(Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]))
