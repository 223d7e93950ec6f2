"""The files of the output preview (meshik/preview/viewer/): the page with the output folder's jobs, the
app, and the three.js and meshoptimizer files it imports with their licences, a fixed list
(vendor_files.txt) copied from the pinned npm packages into meshik/preview/vendor/ when the package is
built. No network: everything is served locally.

    write_viewer(out)           # out/index.html and out/viewer/... (what `make demo` leaves)
    viewer_file("viewer/app.js")  # the path behind one URL of the preview, or None
"""
import json
import shutil
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

from meshik.errors import OutputError

PACKAGE_VIEWER = Path(__file__).resolve().parent / "viewer"
PACKAGE_VENDOR = Path(__file__).resolve().parent / "vendor"
APP_FILES = ("app.js", "viewer.css")


def vendor_files() -> Tuple[str, ...]:
    """The npm files' paths under vendor/ (served as viewer/vendor/<path>), from vendor_files.txt: one
    file a line, its node_modules path then, when it differs, its vendor path; # starts a comment."""
    lines = (Path(__file__).resolve().parent / "vendor_files.txt").read_text(encoding="utf-8").splitlines()
    return tuple(line.split()[-1] for line in lines if line.strip() and not line.startswith("#"))


VENDOR_FILES = vendor_files()


def jobs_of(out_dir: Path) -> List[Dict[str, Any]]:
    """The folder's jobs with a .glb: [{name, glb, report, sheet (or None)}], URLs relative to
    out_dir; a job is out_dir itself or one of its sub-folders holding report.json and <name>.glb."""
    jobs = []
    for folder in [out_dir] + sorted(p for p in out_dir.iterdir() if p.is_dir()):
        glbs = sorted(folder.glob("*.glb"))
        if not ((folder / "report.json").is_file() and glbs):
            continue
        relative = folder.relative_to(out_dir).as_posix()
        prefix = "" if relative == "." else relative + "/"
        name = folder.name if prefix else glbs[0].stem
        sheets = [p for p in (out_dir / f"{folder.name}_contact_sheet.png", folder / "contact_sheet.png") if p.is_file()]
        jobs.append({"name": name, "glb": prefix + glbs[0].name, "report": prefix + "report.json",
                     "sheet": sheets[0].relative_to(out_dir).as_posix() if sheets else None})
    return jobs


def index_html(out_dir: Path) -> str:
    """The preview page for out_dir's jobs (the manifest is inlined as JSON)."""
    manifest = json.dumps({"jobs": jobs_of(out_dir)}).replace("</", "<\\/")
    return (PACKAGE_VIEWER / "index.html").read_text(encoding="utf-8").replace("__MANIFEST__", manifest)


def viewer_file(relative: str) -> Optional[Path]:
    """The file behind URL path `relative` under viewer/ (e.g. "viewer/app.js",
    "viewer/vendor/three/build/three.module.js"), or None when it is not on the fixed lists."""
    if relative.startswith("viewer/vendor/") and relative[len("viewer/vendor/"):] in VENDOR_FILES:
        return PACKAGE_VENDOR / relative[len("viewer/vendor/"):]
    if relative.startswith("viewer/") and relative[len("viewer/"):] in APP_FILES:
        return PACKAGE_VIEWER / relative[len("viewer/"):]
    return None


def check_vendor_files() -> None:
    """OutputError naming the first missing npm file (a development tree not built yet: make build)."""
    for relative in VENDOR_FILES:
        if not (PACKAGE_VENDOR / relative).is_file():
            raise OutputError(f"{PACKAGE_VENDOR / relative}: missing: the preview's npm files are copied there when "
                              "the package is built (make build, after scripts/setup.sh node)")


def write_viewer(out_dir: Path) -> Path:
    """Write out_dir/index.html and out_dir/viewer/ (app and vendor files) so that the folder can be
    served as it is; returns the page's path."""
    check_vendor_files()
    for relative in [f"viewer/{name}" for name in APP_FILES] + [f"viewer/vendor/{name}" for name in VENDOR_FILES]:
        target = out_dir / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(viewer_file(relative), target)
    page = out_dir / "index.html"
    page.write_text(index_html(out_dir), encoding="utf-8")
    return page
