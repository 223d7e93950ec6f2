"""An error-bounded low-rank morph basis for the quantized / meshopt .glb (`--glb-targets basis`),
with every morph weight inside [0, 1].

The frames of an animation repeat (cycles, holds), so their deltas from the rest span far fewer
directions than there are frames. From the eigenvectors of the frames x frames Gram matrix of the
deltas (in grid units), r directions d_j = u_j^T D are fitted to the frames (weights W0, #keys by r).
Readers that map morph targets to shape-key sliders (Blender) clamp weights to [0, 1], so the basis
is moved to the corner of the weights' box: the base becomes rest + sum_j min_k W0_kj d_j and each
target spans its direction's whole range, (max_k W0_kj - min_k W0_kj) d_j, so that the weights run
from 0 to 1. The base and targets are integers in a node unit 1/f of a grid step (the base an
UNSIGNED_SHORT after an offset, the targets SHORTs: they share the base's dequantization), targets
whose range is small are magnified c_j >= 1 times (their weights then stay below 1 / c_j), and the
base and targets are rounded together (Babai's nearest plane over the keys' weights: the base takes
up what the targets' rounding shares across keys, which keeps the corner's error as small as the
rest-centred basis'). r is the smallest rank, and the precision the coarsest (fewest bits), whose decoding,
evaluated as a glTF viewer does (float32 base + sum_j w_kj target_j), keeps every vertex of every
frame within `tolerance` grid units of the frame; None when only one target per frame would do.
"""
from dataclasses import dataclass
from typing import Optional

import numpy as np
from threadpoolctl import threadpool_limits

MAX_BASIS_FRAMES = 1024     # above this, one target per frame (the Gram matrix and the search stay small)
_SHORT_MAX = 2 ** 15 - 1
_USHORT_SPAN = 2 ** 16 - 2   # the base's extent in node units, one short of UNSIGNED_SHORT's for the rounding
_PRECISION_STEPS_PER_OCTAVE = 4  # the precision is searched in steps of 2**(1/4)
_PRECISION_OCTAVES = 16


@dataclass(frozen=True)
class MorphBasis:
    """base: #V by 3 integers, targets: r by #V by 3 integers within a SHORT, both in node units of
    `unit` grid steps (base * unit is the basis' corner in grid coordinates: it may lie outside the
    grid, and its extent per axis fits an UNSIGNED_SHORT); weights: #keys by r float32 in [0, 1]."""
    base: np.ndarray
    targets: np.ndarray
    weights: np.ndarray
    unit: float


def morphed_positions(base: np.ndarray, weights: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """#keys by #V by 3 float32 positions base + sum_j weights[k, j] targets[j], in float32 as a glTF
    viewer computes them. base: #V by 3; weights: #keys by r; targets: r by #V by 3."""
    flat = np.asarray(targets, dtype=np.float32).reshape(len(targets), -1)
    moved = np.asarray(weights, dtype=np.float32) @ flat
    return (np.asarray(base, dtype=np.float32).reshape(1, -1) + moved).reshape((len(weights),) + np.shape(base))


def basis_positions(basis: MorphBasis) -> np.ndarray:
    """#keys by #V by 3 positions in grid units that a viewer decodes from `basis`: the base stored
    from its smallest corner (as the .glb stores it), mixed in float32, then scaled by the node unit."""
    offset = basis.base.min(axis=0)
    return (morphed_positions(basis.base - offset, basis.weights, basis.targets) + offset) * basis.unit


def low_rank_basis(base: np.ndarray, frames: np.ndarray, tolerance: float) -> Optional[MorphBasis]:
    """The smallest basis reproducing every frame within `tolerance` (grid units), or None when it
    would need as many targets as frames (or there are more than MAX_BASIS_FRAMES frames).

    base: #V by 3 integer grid coordinates of the rest; frames: #keys by #V by 3 frames in grid units
    (not rounded: the basis fits the solver's positions, not their rounding noise).
    """
    keys = len(frames)
    if keys < 2 or keys > MAX_BASIS_FRAMES:
        return None
    # Its products are small (keys by 3V by r): one BLAS thread is 3x faster here than a team that
    # contends for the cores (and up to 25x under load), and gives the same bits on every machine.
    with threadpool_limits(limits=1, user_api="blas"):
        return _smallest_basis(base, np.asarray(frames, dtype=np.float64), tolerance)


def _smallest_basis(base: np.ndarray, frames: np.ndarray, tolerance: float) -> Optional[MorphBasis]:
    """low_rank_basis's search, on the calling thread's BLAS settings."""
    keys = len(frames)
    deltas = (frames - base).reshape(keys, -1)
    eigenvalues, eigenvectors = np.linalg.eigh(deltas @ deltas.T)
    order = np.argsort(eigenvalues)[::-1]
    eigenvalues, directions = np.maximum(eigenvalues[order], 0.0), eigenvectors[:, order]
    # a rank whose left-out energy, spread over every vertex of every frame, already exceeds the
    # tolerance cannot pass: the search starts above it
    left_out = np.concatenate([np.cumsum(eigenvalues[::-1])[::-1], [0.0]])
    low = max(1, int(np.argmax(left_out <= tolerance ** 2 * deltas.size / 3)))
    high, found = keys, None
    while low < high:  # bisection for the smallest rank that passes at the finest precision
        rank = (low + high) // 2
        box = _BasisBox(base, deltas, directions[:, :rank].T @ deltas)
        basis = box.fitted(frames, np.inf, tolerance)
        if basis is None:
            low = rank + 1
        else:
            high, found = rank, basis
    if found is None:
        return None
    return _BasisBox(base, deltas, directions[:, :high].T @ deltas).coarsest(frames, tolerance) or found


class _BasisBox:
    """r real directions moved to the corner of their weights' box (grid units, before rounding).

    corner: 3V, the rest plus each direction at its smallest weight; spans: r by 3V, each direction
    times its weights' range (weight 0 at the smallest, 1 at the largest); peaks: r, each span's
    largest coordinate; unit_cap: the finest node unit (units per grid step) at which the corner's
    extent fits an UNSIGNED_SHORT and every span a SHORT.
    """

    def __init__(self, base: np.ndarray, deltas: np.ndarray, directions: np.ndarray):
        """base: #V by 3 rest (grid units); deltas: #keys by 3V frames - rest; directions: r by 3V."""
        weights = np.linalg.lstsq(directions @ directions.T, directions @ deltas.T, rcond=None)[0].T
        low, high = weights.min(axis=0), weights.max(axis=0)
        self.key_weights = (weights - low) / np.maximum(high - low, 1e-300)
        self.corner = np.asarray(base, dtype=np.float64).reshape(-1) + low @ directions
        self.spans = (high - low)[:, None] * directions
        self.peaks = np.maximum(np.abs(self.spans).max(axis=1), 1e-300)
        extent = np.ptp(self.corner.reshape(-1, 3), axis=0).max()
        self.unit_cap = min(_USHORT_SPAN / max(extent, 1e-300), _SHORT_MAX / self.peaks.max())

    def coarsest(self, frames: np.ndarray, tolerance: float) -> Optional[MorphBasis]:
        """The basis at the coarsest precision 2**(e/4) that passes, or None. The search spans from
        _PRECISION_OCTAVES below the node unit cap to the precision that fills a SHORT with the
        smallest span (every target at full precision)."""
        low = int(np.floor(_PRECISION_STEPS_PER_OCTAVE * (np.log2(self.unit_cap) - _PRECISION_OCTAVES)))
        high = int(np.ceil(_PRECISION_STEPS_PER_OCTAVE * np.log2(_SHORT_MAX / self.peaks.min())))
        found = None
        while low < high:
            step = (low + high) // 2
            basis = self.fitted(frames, 2.0 ** (step / _PRECISION_STEPS_PER_OCTAVE), tolerance)
            if basis is None:
                low = step + 1
            else:
                high, found = step, basis
        return found

    def fitted(self, frames: np.ndarray, precision: float, tolerance: float) -> Optional[MorphBasis]:
        """The basis at `precision` (units per grid step): node unit f = min(precision, unit_cap),
        target j = round(q_j span_j) with q_j = min(precision, the most that fits a SHORT) >= f, the
        base round(f corner), the #keys by r weights fitted to #keys by #V by 3 `frames` (grid units)
        and clipped to [0, 1]; None when a decoded frame is farther than tolerance from `frames`."""
        unit = min(precision, self.unit_cap)
        magnified = np.minimum(precision, _SHORT_MAX / self.peaks) / unit
        weights = self.key_weights / magnified
        base, targets = _jointly_rounded(self.corner * unit, self.spans * (unit * magnified)[:, None], weights)
        basis = MorphBasis(base=base.reshape(-1, 3).astype(np.int64),
                           targets=targets.reshape(len(targets), -1, 3).astype(np.int32),
                           weights=np.clip(weights, 0.0, 1.0).astype(np.float32), unit=1.0 / unit)
        if not np.all(np.linalg.norm(basis_positions(basis) - frames, axis=2) <= tolerance):
            return None
        return basis


def _jointly_rounded(base: np.ndarray, targets: np.ndarray, weights: np.ndarray):
    """(base, targets) rounded to integers together so that each decoded key, base + weights @ targets,
    stays close to its unrounded value: per coordinate, Babai's nearest plane in the lattice of the
    columns [1, weights] (the base's rounding absorbs what the targets' share across keys); a column
    that depends on the ones before it is rounded alone.
    base: 3V reals; targets: r by 3V reals; weights: #keys by r; returns 3V and r by 3V floats."""
    columns = np.concatenate([np.ones((len(weights), 1)), weights], axis=1)
    _, triangle = np.linalg.qr(columns)
    unrounded = np.concatenate([base[None], targets])
    goal = triangle @ unrounded  # the unrounded keys in the QR frame
    independent = np.abs(np.diag(triangle)) > 1e-6 * np.abs(np.diag(triangle)).max()
    rounded = np.zeros_like(goal)
    for i in range(len(goal) - 1, -1, -1):
        rounded[i] = np.rint((goal[i] - triangle[i, i + 1:] @ rounded[i + 1:]) / triangle[i, i]) if independent[i] \
            else np.rint(unrounded[i])
    return rounded[0], rounded[1:]
