"""Outputs that appear complete or not at all.

A job writes its files into a hidden staging folder. How commit() moves them into place depends
on where the destination lies:
- Inside a folder that the run owns as a whole (a batch's --out, given as `within`): the staging
  folder is the destination's sibling, holds the complete new result with report.json, and is
  swapped with the destination in one directory-entry exchange (meshik.outputs.folder_swap). At every
  instant the destination is the complete old result or the complete new one. Files in the old
  folder that no run provably wrote (a user's notes, an edited output) are hard-linked across first.
- Otherwise (`meshik pose --out FOLDER`: swapping FOLDER itself would write beside it, outside
  --out), and where the file system cannot swap or hard-link: the staging folder lies inside the
  destination, and commit() takes the previous report.json out of place, moves each file to its
  final name (an atomic rename on one file system) and puts the new report.json in place last. So
  whenever report.json is present, every file it lists has exactly the bytes it records (their
  SHA-256): a run killed while it commits leaves no report (the folder reads as incomplete, never
  as the old result beside new files), and the next run completes it.
An interrupted job leaves only its hidden staging folder, which the next run there removes: a
folder counts as abandoned staging only when it holds the marker file the run that made it wrote
(a user's own folder named like one is left alone) and that run's process no longer runs.

No output may land on one of the run's inputs: check_not_inputs compares every output path with
the inputs by real path and by (device, inode) before anything is written, and commit() checks again.

A run removes an earlier output only when it can prove that it wrote it: the earlier report must
list the file inside the destination with the SHA-256 of the bytes written then, the file on disk
must still have exactly those bytes, and it must not be one of this run's inputs. A report.json
written by hand or by another tool therefore never deletes anything.
"""
import hashlib
import json
import os
import shutil
import uuid
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, Optional

from meshik.errors import OutputError
from meshik.outputs.folder_swap import SwapUnavailable, carry_over, swap_in
from meshik.outputs.safe_paths import inside

REPORT_NAME = "report.json"
_STAGING_PREFIX = ".meshik-partial-"
# Where commit() keeps the previous report while it moves the new files into place.
_REPLACED_REPORT_NAME = ".meshik-replaced-report.json"
# Written into every staging folder when it is made: only folders holding it are ever removed as stale.
_STAGING_MARKER = ".meshik-staging"


def check_not_inputs(destination: Path, relatives: Iterable[str], inputs: Iterable) -> None:
    """OutputError naming the output and the input when an output file `destination/relative`
    (relatives: e.g. "report.json", "frames/0001.obj") is one of `inputs`, by real path or by
    (device, inode) (a hard link or a link to it); None otherwise. Writes nothing."""
    input_list = [Path(p) for p in inputs]
    real_inputs = {os.path.realpath(p): p for p in input_list}
    input_ids = {_file_id(p): p for p in input_list} if input_list else {}
    input_ids.pop(None, None)
    for relative in relatives:
        target = Path(destination) / relative
        same = real_inputs.get(os.path.realpath(target)) or input_ids.get(_file_id(target))
        if same is not None:
            raise OutputError(f"{target}: this output would replace the input {same}: choose another output folder")


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
    return _read_json(Path(destination) / REPORT_NAME)


def _read_json(path: Path) -> Optional[Dict[str, Any]]:
    """The JSON object in the file at `path`, or None when it is missing, unreadable or no object."""
    try:
        value = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return value if isinstance(value, dict) else None


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

    within: a folder the run owns as a whole that contains `destination` (a batch's --out), or
    None; when `destination` lies strictly inside it, commit() swaps the whole folder in at once.
    Use as a context manager: leaving the block without commit() (an error, an interrupt)
    deletes the staging folder (and the destination folder if this created it and it is empty),
    leaving the destination as it was.
    """

    def __init__(self, destination: Path, within: Optional[Path] = None):
        """Create a fresh staging folder (and `destination` where files move in one by one); OutputError if impossible."""
        self.destination = Path(destination)
        check_writable(self.destination)
        self.swapping = within is not None and self.destination.absolute().parent.is_relative_to(Path(within).absolute())
        self.created = not self.destination.exists() and not self.swapping
        home = self.destination.parent if self.swapping else self.destination
        try:
            home.mkdir(parents=True, exist_ok=True)
            _remove_abandoned_staging(home)
            if self.swapping and self.destination.is_dir():  # left there by an earlier file-by-file commit
                _remove_abandoned_staging(self.destination)
            suffix = f"-{self.destination.name}" if self.swapping else ""
            self.staging = home / f"{_STAGING_PREFIX}{os.getpid()}-{uuid.uuid4().hex[:8]}{suffix}"
            self.staging.mkdir()
            (self.staging / _STAGING_MARKER).write_bytes(b"")
        except OSError as error:
            raise OutputError(f"{self.destination}: cannot create the output folder: {error.strerror or error}") from None
        self.files: Dict[str, int] = {}
        self.digests: Dict[str, str] = {}

    def write(self, relative: str, data: bytes) -> None:
        """Write the output file `relative` (e.g. "frames/0001.drc") into the staging folder.

        OutputError when `relative` is not a path inside the destination (e.g. a frame named '..')
        or the file cannot be written (a full disk), naming the destination and `relative`.
        """
        self.save(relative, lambda path: path.write_bytes(data))

    def save(self, relative: str, writer: Callable[[Path], Any]) -> None:
        """Write the output file `relative` with writer(path) (e.g. another library's mesh writer).

        Errors as write(): a failed writer (OSError, or a ValueError from a library) becomes one
        OutputError naming the destination, `relative`, the reason and the space left on that disk.
        """
        path = self._staging_path(relative)
        try:
            writer(path)
        except (OSError, ValueError) as error:
            if isinstance(error, OSError):
                reason = f"cannot write {relative}: {error.strerror or error}"
            else:
                reason = f"{relative}: {str(error).removeprefix(f'{path}: ').replace(str(path), relative)}"
            raise OutputError(f"{self.destination}: {reason} ({_free_bytes(self.staging)} bytes free on that disk)") from None
        self.files[relative] = path.stat().st_size
        self.digests[relative] = _file_sha256(path)

    def _staging_path(self, relative: str) -> Path:
        """Where output `relative` is written in the staging folder (its folder created); OutputError if it
        is no path inside the destination or a name the run keeps for itself."""
        inside(self.destination, relative, "output file")
        if relative in (REPORT_NAME, _REPLACED_REPORT_NAME, _STAGING_MARKER):
            raise OutputError(f"{self.destination}: '{relative}' is a name the run keeps for itself")
        path = inside(self.staging, relative, "output file")
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    def commit(self, report: Dict[str, Any], inputs: Iterable = ()) -> Dict[str, Any]:
        """Put every file and report.json in place, the report with "outputs" (name -> bytes) and
        "output_sha256" (name -> SHA-256 of its bytes): by one folder swap where possible (see the
        module's note), else file by file with the report last.

        An output of the previous report that is not produced now is removed only when it provably
        came from an earlier run (see the module's note); `inputs` are this run's input files, never
        removed. Returns the report as written.
        """
        replaced = self.destination / _REPLACED_REPORT_NAME
        inputs = list(inputs)
        check_not_inputs(self.destination, [*self.files, REPORT_NAME], inputs)
        previous = read_report(self.destination) or _read_json(replaced) or {}
        report = dict(report, outputs=dict(sorted(self.files.items())),
                      output_sha256=dict(sorted(self.digests.items())))
        try:
            (self.staging / REPORT_NAME).write_text(json.dumps(report, indent=1))
            stale = _provably_written(self.destination, previous, set(self.files), inputs)
            if not (self.swapping and self._swap(stale)):
                self._move_file_by_file(stale)
        except OSError as error:
            raise OutputError(f"{self.destination}: cannot move the outputs into place: {error.strerror or error}") from None
        finally:
            shutil.rmtree(self.staging, ignore_errors=True)
        return report

    def _swap(self, stale: Iterable[Path]) -> bool:
        """Swap the staging folder (with what the old folder must keep linked in) for the destination.

        Returns False, having changed nothing in the destination, where the file system cannot do
        it; the old folder then lies at the staging folder's name, removed by commit().
        """
        dropped = {path.relative_to(self.destination).as_posix() for path in stale}
        dropped |= set(self.files) | {REPORT_NAME, _REPLACED_REPORT_NAME, _STAGING_MARKER}
        marker = self.staging / _STAGING_MARKER
        try:
            if self.destination.is_dir():
                carry_over(self.destination, self.staging, dropped.__contains__)
            marker.unlink()  # the staging folder becomes the destination
            swap_in(self.staging, self.destination)
        except SwapUnavailable:
            marker.write_bytes(b"")
            return False
        if self.staging.is_dir():  # the old folder, now at the staging name: stale if a kill comes before its removal
            marker.write_bytes(b"")
        return True

    def _move_file_by_file(self, stale: Iterable[Path]) -> None:
        """Move the staged files into the destination one by one and the staged report.json last."""
        replaced = self.destination / _REPLACED_REPORT_NAME
        self.destination.mkdir(parents=True, exist_ok=True)
        # From here until the new report is in place the folder has no report.json: a run killed
        # meanwhile leaves it marked incomplete (never an old report beside new files), and the
        # next run still finds the old report's list under _REPLACED_REPORT_NAME.
        if (self.destination / REPORT_NAME).exists():
            os.replace(self.destination / REPORT_NAME, replaced)
        for relative in self.files:
            target = self.destination / relative
            try:
                target.parent.mkdir(parents=True, exist_ok=True)
                os.replace(self.staging / relative, target)
            except OSError as error:
                raise OutputError(f"{target}: cannot move this output into place: {error.strerror or error} (the folder "
                                  f"has no report.json until a run completes)") from None
        for path in stale:
            path.unlink()
        os.replace(self.staging / REPORT_NAME, self.destination / REPORT_NAME)
        replaced.unlink(missing_ok=True)

    def __enter__(self) -> "StagedOutput":
        return self

    def __exit__(self, *exc_info) -> None:
        shutil.rmtree(self.staging, ignore_errors=True)
        if self.created and self.destination.is_dir() and not any(self.destination.iterdir()):
            self.destination.rmdir()


def _provably_written(destination: Path, previous: Dict[str, Any], kept: set, inputs: Iterable) -> Iterable[Path]:
    """Files of the `previous` report that are not `kept` and that an earlier run provably wrote.

    A file qualifies when it is listed under "output_sha256" with a name inside `destination`,
    is a regular file (not a link) whose bytes still hash to the listed digest, and is none of
    `inputs` (paths of this run's input files). Anything else in a report is ignored.
    """
    digests = previous.get("output_sha256")
    if not isinstance(digests, dict):
        return []
    input_ids = {_file_id(Path(p)) for p in inputs} - {None}
    stale = []
    for relative, digest in digests.items():
        if relative in kept or not isinstance(relative, str) or not isinstance(digest, str):
            continue
        try:
            path = inside(destination, relative, "output file")
        except OutputError:
            continue
        if path.is_symlink() or not path.is_file() or _file_id(path) in input_ids:
            continue
        if _file_sha256(path) == digest:
            stale.append(path)
    return stale


def _free_bytes(folder: Path) -> int:
    """Bytes an unprivileged writer may still use on the file system of `folder` (0 when unknown)."""
    try:
        status = os.statvfs(folder)
    except OSError:
        return 0
    return status.f_bavail * status.f_frsize


def _file_id(path: Path):
    """(device, inode) of an existing file, or None."""
    try:
        status = path.stat()
    except OSError:
        return None
    return status.st_dev, status.st_ino


def _file_sha256(path: Path) -> str:
    """SHA-256 (hex) of a file's bytes, read in 1 MiB blocks."""
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _remove_abandoned_staging(destination: Path) -> None:
    """Delete staging folders in `destination` left by processes that no longer run: a real folder
    (not a link) named like one, holding the marker file as a regular file."""
    for folder in destination.glob(f"{_STAGING_PREFIX}*"):
        pid = folder.name[len(_STAGING_PREFIX):].split("-")[0]
        if not pid.isdigit() or folder.is_symlink() or not (folder / _STAGING_MARKER).is_file() \
                or (folder / _STAGING_MARKER).is_symlink():
            continue
        if not _process_alive(int(pid)):
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
