"""Example sets kept in memory between jobs of one process (a batch worker), so that jobs posing the
same character do not load its meshes and rebuild its features (meshik.ExampleSet) each time.

Entries are keyed by the SHA-256 of the files' contents (rest mesh then examples, in order), so a
file edited between two jobs is loaded again and a copy at another path is found. The cache holds
at most `max_bytes` (an estimate: the mesh arrays plus the features' measured footprint); the least
recently used entries go first.
"""
import dataclasses
import hashlib
import threading
from collections import OrderedDict
from pathlib import Path
from typing import Callable, Optional, Sequence, Tuple

from meshik.inputs.meshio import ExampleMeshes, load_example_set

# Resident memory of a meshik.ExampleSet per triangle and example, measured on horse-poses (132 B)
# and elephant-poses (130 B) as the growth of a fresh process's RSS while building one (features
# stored in single precision, the default; 191 and 211 B with feature_precision="double").
FEATURE_BYTES_PER_TRIANGLE_EXAMPLE = 150
_CHUNK = 1 << 20


class _Entry:
    """One cached example set: its meshes, and its features built on first use."""

    def __init__(self, meshes: ExampleMeshes):
        self.meshes = meshes
        self._features = None
        self._lock = threading.Lock()

    def features(self, threads: Optional[int] = None):
        """The meshik.ExampleSet of the meshes, built once (on `threads` threads, None: all cores; the
        features are the same for any count). Raises meshik.InputError when the core rejects the meshes."""
        import meshik

        with self._lock:
            if self._features is None:
                self._features = meshik.ExampleSet(self.meshes.rest, self.meshes.faces, list(self.meshes.examples),
                                                   threads=threads)
            return self._features

    def estimated_bytes(self) -> int:
        """The entry's memory estimate: mesh arrays plus the features (counted whether built or not)."""
        meshes = self.meshes
        arrays = meshes.rest.nbytes + meshes.faces.nbytes + sum(e.nbytes for e in meshes.examples)
        return arrays + FEATURE_BYTES_PER_TRIANGLE_EXAMPLE * len(meshes.faces) * max(len(meshes.examples), 1)


class ExampleSetCache:
    """A bounded, thread-safe least-recently-used cache of example sets keyed by content hash."""

    def __init__(self, max_bytes: int):
        """max_bytes: memory bound of all entries together (0 keeps nothing)."""
        self.max_bytes = int(max_bytes)
        self._entries: "OrderedDict[str, _Entry]" = OrderedDict()
        self._lock = threading.Lock()
        self.hits = self.misses = 0

    def get(self, rest_path, example_paths: Sequence) -> Tuple[ExampleMeshes, Callable[[Optional[int]], object]]:
        """(meshes, features) of these files: meshes as load_example_set returns them (with the paths
        given here), features(threads) their meshik.ExampleSet, built at most once per cached entry.
        Files whose contents were seen before come from memory. Raises MeshFileError as
        load_example_set does, meshik.InputError from features(threads) when the core rejects the meshes."""
        rest_path, example_paths = Path(rest_path), tuple(Path(p) for p in example_paths)
        key = content_key([rest_path, *example_paths])
        with self._lock:
            entry = self._entries.get(key) if key is not None else None
            if entry is not None:
                self._entries.move_to_end(key)
                self.hits += 1
            else:
                self.misses += 1
        if entry is None:
            entry = _Entry(load_example_set(rest_path, example_paths))
            if key is not None:
                self._keep(key, entry)
        meshes = dataclasses.replace(entry.meshes, rest_path=rest_path, example_paths=example_paths)
        return meshes, entry.features

    def bytes_used(self) -> int:
        """Estimated memory of the entries kept."""
        with self._lock:
            return sum(e.estimated_bytes() for e in self._entries.values())

    def release(self, wanted: int) -> int:
        """Drop least recently used entries until their estimates add up to `wanted` bytes (or none
        is left); returns the estimated bytes dropped."""
        dropped = 0
        with self._lock:
            while self._entries and dropped < wanted:
                dropped += self._entries.popitem(last=False)[1].estimated_bytes()
        return dropped

    def _keep(self, key: str, entry: _Entry) -> None:
        """Store an entry, dropping the least recently used ones to stay within max_bytes."""
        size = entry.estimated_bytes()
        with self._lock:
            if size > self.max_bytes:
                return
            self._entries[key] = entry
            while sum(e.estimated_bytes() for e in self._entries.values()) > self.max_bytes:
                self._entries.popitem(last=False)


def content_key(paths: Sequence[Path]) -> Optional[str]:
    """SHA-256 over the SHA-256 of each file's bytes, in order; None when a file cannot be read
    (the loader then reports it in its own words)."""
    overall = hashlib.sha256()
    for path in paths:
        digest = hashlib.sha256()
        try:
            with open(path, "rb") as stream:
                for chunk in iter(lambda: stream.read(_CHUNK), b""):
                    digest.update(chunk)
        except OSError:
            return None
        overall.update(digest.digest())
    return overall.hexdigest()
