"""Shared pytest fixtures: where the sample meshes and the real example sets are."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "sample_meshes"
SHARED_DATA = pathlib.Path(os.environ.get("MESHIK_SHARED_DATA", ROOT.parent / "shared" / "data"))


@pytest.fixture(scope="session")
def samples_dir() -> pathlib.Path:
    """The project's own generated example sets (sample_meshes/)."""
    return SAMPLES


@pytest.fixture(scope="session")
def shared_data() -> pathlib.Path:
    """../shared/data (real example sets); skips the test with a clear message when absent."""
    if not SHARED_DATA.is_dir():
        pytest.skip(f"real example sets not found at {SHARED_DATA} (set MESHIK_SHARED_DATA)")
    return SHARED_DATA


def example_set_files(folder: pathlib.Path):
    """(rest_path, [example paths]) of a shared/data folder: *reference.obj and the numbered files."""
    rest = next(folder.glob("*reference.obj"))
    examples = sorted((p for p in folder.glob("*.obj") if p != rest),
                      key=lambda p: int("".join(c for c in p.stem if c.isdigit()) or 0))
    return rest, examples
