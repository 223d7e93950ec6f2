"""Outputs that appear complete or not at all.

A job writes its files into a hidden staging folder inside the destination; commit() then moves
each file to its final name (an atomic rename on one file system) and writes report.json last,
so a finished report means every file it lists is complete. An interrupted job leaves only the
hidden staging folder, which the next run in that destination removes.
"""
import json
import os
import shutil
import uuid
from pathlib import Path
from typing import Any, Dict, Optional

from meshik.errors import OutputError

REPORT_NAME = "report.json"
_STAGING_PREFIX = ".meshik-partial-"


def check_writable(destination: Path) -> None:
    """OutputError unless `destination` is, or can be created as, a writable folder. Creates nothing."""
    destination = Path(destination).absolute()
    existing = destination
    while not existing.exists():
        if existing.parent == existing:
            break
        existing = existing.parent
    if existing.exists() and not existing.is_dir():
        what = "is a file" if existing == destination else f"cannot be created: {existing} is a file"
        raise OutputError(f"{destination}: output folder {what}")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise OutputError(f"{destination}: output folder is not writable (no write permission on {existing})")


def read_report(destination: Path) -> Optional[Dict[str, Any]]:
    """The report.json of a destination if present and readable JSON, else None."""
    try:
        return json.loads((Path(destination) / REPORT_NAME).read_text())
    except (OSError, ValueError):
        return None


def is_complete(destination: Path, job_key: str) -> bool:
    """Whether `destination` holds a finished job with this key: its report and every listed file, at its size."""
    report = read_report(destination)
    if not report or report.get("job_key") != job_key or not isinstance(report.get("outputs"), dict):
        return False
    for name, size in report["outputs"].items():
        path = Path(destination) / name
        if not path.is_file() or path.stat().st_size != size:
            return False
    return True


class StagedOutput:
    """A job's outputs, written under a hidden staging folder and moved into `destination` by commit().

    Use as a context manager: leaving the block without commit() (an error, an interrupt)
    deletes the staging folder (and the destination folder if this created it and it is empty),
    leaving the destination as it was.
    """

    def __init__(self, destination: Path):
        """Create `destination` (if needed) and a fresh staging folder in it; OutputError if impossible."""
        self.destination = Path(destination)
        check_writable(self.destination)
        self.created = not self.destination.exists()
        try:
            self.destination.mkdir(parents=True, exist_ok=True)
            _remove_abandoned_staging(self.destination)
            self.staging = self.destination / f"{_STAGING_PREFIX}{os.getpid()}-{uuid.uuid4().hex[:8]}"
            self.staging.mkdir()
        except OSError as error:
            raise OutputError(f"{self.destination}: cannot create the output folder: {error.strerror or error}") from None
        self.files: Dict[str, int] = {}

    def write(self, relative: str, data: bytes) -> None:
        """Write the output file `relative` (e.g. "frames/0001.drc") into the staging folder."""
        path = self.path(relative)
        path.write_bytes(data)
        self.files[relative] = len(data)

    def path(self, relative: str) -> Path:
        """Staging path for an output written by another library; call added(relative) once written."""
        path = self.staging / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    def added(self, relative: str) -> None:
        """Record a file written at path(relative) by other means."""
        self.files[relative] = (self.staging / relative).stat().st_size

    def commit(self, report: Dict[str, Any]) -> Dict[str, Any]:
        """Move every file into place, then write report.json (with "outputs": name -> bytes) last.

        Files listed by a previous report in this destination but not produced now are removed.
        Returns the report as written.
        """
        previous = read_report(self.destination) or {}
        report = dict(report, outputs=dict(sorted(self.files.items())))
        try:
            for relative in self.files:
                target = self.destination / relative
                target.parent.mkdir(parents=True, exist_ok=True)
                os.replace(self.staging / relative, target)
            for relative in (previous.get("outputs") or {}):
                if relative not in self.files and _inside(self.destination, relative):
                    (self.destination / relative).unlink(missing_ok=True)
            staged_report = self.staging / REPORT_NAME
            staged_report.write_text(json.dumps(report, indent=1))
            os.replace(staged_report, self.destination / REPORT_NAME)
        except OSError as error:
            raise OutputError(f"{self.destination}: cannot move the outputs into place: {error.strerror or error}") from None
        finally:
            shutil.rmtree(self.staging, ignore_errors=True)
        return report

    def __enter__(self) -> "StagedOutput":
        return self

    def __exit__(self, *exc_info) -> None:
        shutil.rmtree(self.staging, ignore_errors=True)
        if self.created and not any(self.destination.iterdir()):
            self.destination.rmdir()


def _inside(folder: Path, relative: str) -> bool:
    """Whether `relative` names a path inside `folder` (guards against '..' in a tampered report)."""
    try:
        (folder / relative).resolve().relative_to(folder.resolve())
        return True
    except (ValueError, OSError):
        return False


def _remove_abandoned_staging(destination: Path) -> None:
    """Delete staging folders in `destination` left by processes that no longer run."""
    for folder in destination.glob(f"{_STAGING_PREFIX}*"):
        pid = folder.name[len(_STAGING_PREFIX):].split("-")[0]
        if pid.isdigit() and not _process_alive(int(pid)):
            shutil.rmtree(folder, ignore_errors=True)


def _process_alive(pid: int) -> bool:
    """Whether a process with this id exists (signal 0 probe)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
