"""How far the compressed outputs of a job decode from the solver's frames: each written .drc frame
and .glb is decoded again and its largest position error recorded, as a fraction of the diagonal
of the animation's bounding box (every frame), beside its bytes, for report.json."""
from typing import Any, Dict

import numpy as np

from meshik.export.draco import decode
from meshik.export.glb_layout import rows_of_ids
from meshik.export.glb_readers import readers_of
from meshik.export.glb_reader import read_animation_glb


class OutputErrors:
    """Bytes and largest decoded position error of a job's .drc frames (together) and .glb."""

    def __init__(self, frames: np.ndarray, vertex_ids: np.ndarray):
        """frames: #frames by #V by 3 solver positions; vertex_ids: #V distinct ids the files carry."""
        self.frames = np.asarray(frames, dtype=np.float64)
        self.vertex_ids = np.asarray(vertex_ids)
        points = self.frames.reshape(-1, 3)
        self.diagonal = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0))) or 1.0
        self.drc_frames, self.drc_bytes, self.drc_error = 0, 0, 0.0
        self.glbs: Dict[str, Dict[str, Any]] = {}

    def add_drc_frame(self, data: bytes) -> None:
        """Record the next frame's .drc bytes (frames are added in order)."""
        decoded = decode(data)
        expected = self.frames[self.drc_frames][rows_of_ids(self.vertex_ids, decoded.vertex_ids)]
        self.drc_error = max(self.drc_error, self._error(decoded.vertices, expected))
        self.drc_frames += 1
        self.drc_bytes += len(data)

    def add_glb(self, name: str, variant: str, data: bytes, grid) -> None:
        """Record the .glb `name` of the given variant quantized on `grid` (a QuantizationGrid; every
        frame is compared)."""
        animation = read_animation_glb(data)
        expected = self.frames[:, rows_of_ids(self.vertex_ids, animation.vertex_ids)]
        self.glbs[name] = {"variant": variant, "bytes": len(data), "position_bits": grid.bits, "grid_step": grid.step,
                           "morph_targets": int(animation.weights.shape[1]),
                           "max_position_error": self._error(animation.frames, expected),
                           "readers": readers_of(variant)}

    def _error(self, decoded: np.ndarray, expected: np.ndarray) -> float:
        """Largest distance between decoded and expected (..., 3) positions over the diagonal;
        ValueError when not finite."""
        error = float(np.linalg.norm(decoded - expected, axis=-1).max()) / self.diagonal
        if not np.isfinite(error):
            raise ValueError("a compressed output decodes to non-finite positions")
        return error

    def report(self) -> Dict[str, Dict[str, Any]]:
        """{"frames/*.drc": {files, bytes, max_position_error}, "<job>.glb": {variant, bytes,
        position_bits, grid_step, morph_targets, max_position_error, readers (glb_readers.readers_of)}},
        only the outputs written."""
        entries: Dict[str, Dict[str, Any]] = {}
        if self.drc_frames:
            entries["frames/*.drc"] = {"files": self.drc_frames, "bytes": self.drc_bytes,
                                       "max_position_error": self.drc_error}
        entries.update(self.glbs)
        return entries
