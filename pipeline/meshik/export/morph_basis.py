"""An error-bounded low-rank morph basis for the quantized / meshopt .glb (`--glb-targets basis`).

The frames of an animation repeat (cycles, holds), so their deltas from the base span far fewer
directions than there are frames. From the eigenvectors of the frames x frames Gram matrix of the
deltas (in grid units), r basis targets B_j = u_j^T D are rounded to integers at a scale s_j (the
same for every target, capped so each fits a SHORT: the weights are free floats, the targets share
the base's dequantization), and the keys x r weights are refitted by least squares to the rounded
targets. r is the smallest rank, and the scale the coarsest (fewest bits), whose decoding, evaluated
as a glTF viewer does (float32 base + sum_j w_kj target_j), keeps every vertex of every frame within
`tolerance` grid units of the frame; None when only one target per frame would do.
"""
from dataclasses import dataclass
from typing import Optional

import numpy as np
from threadpoolctl import threadpool_limits

MAX_BASIS_FRAMES = 1024     # above this, one target per frame (the Gram matrix and the search stay small)
_SHORT_MAX = 2 ** 15 - 1
_SCALE_STEPS_PER_OCTAVE = 4  # the scale is searched in steps of 2**(1/4)
_SCALE_OCTAVES = 16


@dataclass(frozen=True)
class MorphBasis:
    """targets: r by #V by 3 integers within a SHORT (grid units); weights: #keys by r float32."""
    targets: np.ndarray
    weights: np.ndarray


def morphed_positions(base: np.ndarray, weights: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """#keys by #V by 3 float32 positions base + sum_j weights[k, j] targets[j], in float32 as a glTF
    viewer computes them. base: #V by 3; weights: #keys by r; targets: r by #V by 3."""
    flat = np.asarray(targets, dtype=np.float32).reshape(len(targets), -1)
    moved = np.asarray(weights, dtype=np.float32) @ flat
    return (np.asarray(base, dtype=np.float32).reshape(1, -1) + moved).reshape((len(weights),) + np.shape(base))


def low_rank_basis(base: np.ndarray, frames: np.ndarray, tolerance: float) -> Optional[MorphBasis]:
    """The smallest basis reproducing every frame within `tolerance` (grid units), or None when it
    would need as many targets as frames (or there are more than MAX_BASIS_FRAMES frames).

    base: #V by 3 integer grid coordinates of the base; frames: #keys by #V by 3 frames in grid units
    (not rounded: the basis fits the solver's positions, not their rounding noise).
    """
    keys = len(frames)
    if keys < 2 or keys > MAX_BASIS_FRAMES:
        return None
    # Its products are small (keys by 3V by r): one BLAS thread is 3x faster here than a team that
    # contends for the cores (and up to 25x under load), and gives the same bits on every machine.
    with threadpool_limits(limits=1, user_api="blas"):
        return _smallest_basis(base, frames, tolerance)


def _smallest_basis(base: np.ndarray, frames: np.ndarray, tolerance: float) -> Optional[MorphBasis]:
    """low_rank_basis's search, on the calling thread's BLAS settings."""
    keys = len(frames)
    deltas = (np.asarray(frames, dtype=np.float64) - base).reshape(keys, -1)
    eigenvalues, eigenvectors = np.linalg.eigh(deltas @ deltas.T)
    order = np.argsort(eigenvalues)[::-1]
    eigenvalues, directions = np.maximum(eigenvalues[order], 0.0), eigenvectors[:, order]
    # a rank whose left-out energy, spread over every vertex of every frame, already exceeds the
    # tolerance cannot pass: the search starts above it
    left_out = np.concatenate([np.cumsum(eigenvalues[::-1])[::-1], [0.0]])
    low = max(1, int(np.argmax(left_out <= tolerance ** 2 * deltas.size / 3)))
    high, found = keys, None
    while low < high:  # bisection for the smallest rank that passes at the finest scale
        rank = (low + high) // 2
        basis = _fitted(base, frames, deltas, directions[:, :rank].T @ deltas, np.inf, tolerance)
        if basis is None:
            low = rank + 1
        else:
            high, found = rank, basis
    if found is None:
        return None
    return _coarsest(base, frames, deltas, directions[:, :high].T @ deltas, tolerance) or found


def _coarsest(base: np.ndarray, frames: np.ndarray, deltas: np.ndarray, directions: np.ndarray,
              tolerance: float) -> Optional[MorphBasis]:
    """The basis of the r by 3V `directions` at the coarsest scale 2**(e/4) that passes, or None.
    The search spans from _SCALE_OCTAVES below the scale that fills a SHORT with the largest
    direction to the one that fills it with the smallest (every target at full precision)."""
    peaks = np.maximum(np.abs(directions).max(axis=1), 1e-300)
    low = int(np.floor(_SCALE_STEPS_PER_OCTAVE * (np.log2(_SHORT_MAX / peaks.max()) - _SCALE_OCTAVES)))
    high = int(np.ceil(_SCALE_STEPS_PER_OCTAVE * np.log2(_SHORT_MAX / peaks.min())))
    found = None
    while low < high:
        step = (low + high) // 2
        basis = _fitted(base, frames, deltas, directions, 2.0 ** (step / _SCALE_STEPS_PER_OCTAVE), tolerance)
        if basis is None:
            low = step + 1
        else:
            high, found = step, basis
    return found


def _fitted(base: np.ndarray, frames: np.ndarray, deltas: np.ndarray, directions: np.ndarray, scale: float,
            tolerance: float) -> Optional[MorphBasis]:
    """Targets round(s_j directions_j) with s_j = min(scale, the largest that fits a SHORT), weights
    fitted to #keys by 3V `deltas`; None when a decoded frame is farther than tolerance from `frames`."""
    peaks = np.maximum(np.abs(directions).max(axis=1), 1e-300)
    targets = np.rint(directions * np.minimum(scale, _SHORT_MAX / peaks)[:, None])
    weights = np.linalg.lstsq(targets @ targets.T, targets @ deltas.T, rcond=None)[0].T.astype(np.float32)
    targets = targets.reshape(len(targets), -1, 3).astype(np.int32)
    decoded = morphed_positions(base, weights, targets)
    if not np.all(np.linalg.norm(decoded - frames, axis=2) <= tolerance):
        return None
    return MorphBasis(targets=targets, weights=weights)
