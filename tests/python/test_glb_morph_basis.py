"""The low-rank morph basis of the quantized / meshopt .glb (`--glb-targets basis`): a periodic
animation gets fewer targets than frames, a full-rank one falls back to one target per frame, and
every frame decodes (float32, as a viewer mixes the targets) within the grid's rounding."""
import numpy as np
import pytest

from meshik.export import draco as export_draco
from meshik.export.glb_layout import rows_of_ids
from meshik.export.glb_reader import read_animation_glb
from meshik.export.glb_quantized import BASIS_TOLERANCE, quantized_animation_glb
from meshik.export.glb_container import split_glb
from meshik.export.morph_basis import MAX_BASIS_FRAMES, low_rank_basis, morphed_positions


def sheet(side: int):
    """(rest #V by 3, faces #F by 3) of a side x side grid of unit squares, two triangles each."""
    xs, ys = np.meshgrid(np.arange(side, dtype=float), np.arange(side, dtype=float))
    rest = np.c_[xs.ravel(), ys.ravel(), np.zeros(side * side)]
    corners = [(r * side + c, r * side + c + 1, (r + 1) * side + c, (r + 1) * side + c + 1)
               for r in range(side - 1) for c in range(side - 1)]
    faces = [[a, b, c] for a, b, c, _ in corners] + [[b, d, c] for _, b, c, d in corners]
    return rest, np.array(faces)


def write_and_read(rest, faces, frames, targets="basis", bits=12):
    """(read-back AnimationGlb, rows of the file's vertices in rest, grid, glTF JSON) of a meshopt .glb."""
    grid = export_draco.animation_grid(np.concatenate([frames, rest[None]]), bits)
    names = [f"f{k}" for k in range(len(frames))]
    data = quantized_animation_glb(rest, faces, frames, names, np.arange(len(rest)), grid, 24.0, "t", "test",
                                   targets=targets)
    read = read_animation_glb(data)
    assert read.frame_names == tuple(names)
    return read, rows_of_ids(np.arange(len(rest)), read.vertex_ids), grid, split_glb(data)[0]


def periodic_frames(rest: np.ndarray, count: int, period: int) -> np.ndarray:
    """count frames of rest bent by two waves whose amplitudes repeat every `period` frames."""
    phase = 2 * np.pi * np.arange(count) / period
    bend = np.c_[np.zeros(len(rest)), np.zeros(len(rest)), np.sin(rest[:, 0] / 3)]
    twist = np.c_[-rest[:, 1] * 0.1, rest[:, 0] * 0.1, np.cos(rest[:, 1] / 2)]
    return rest + 2 * np.sin(phase)[:, None, None] * bend + np.cos(3 * phase)[:, None, None] * twist


def test_a_periodic_animation_gets_fewer_targets_within_the_grid():
    rest, faces = sheet(12)
    frames = periodic_frames(rest, 40, 10)
    read, rows, grid, document = write_and_read(rest, faces, frames)
    targets = document["meshes"][0]["primitives"][0]["targets"]
    assert 1 < len(targets) < 10 and read.weights.shape == (40, len(targets))
    assert np.linalg.norm(read.frames - frames[:, rows], axis=2).max() <= grid.step * np.sqrt(3) / 2
    weights = document["accessors"][document["animations"][0]["samplers"][0]["output"]]
    assert "sparse" not in weights and weights["count"] == 40 * len(targets)
    assert len(document["meshes"][0]["weights"]) == len(targets)
    for target in targets:  # SHORT, not normalized, with the min / max glTF requires of morph POSITION
        entry = document["accessors"][target["POSITION"]]
        assert entry["componentType"] == 5122 and not entry.get("normalized", False)
        assert -32767 <= min(entry["min"]) and max(entry["max"]) <= 32767
    per_frame, _, _, document = write_and_read(rest, faces, frames, targets="frames")
    assert len(document["meshes"][0]["primitives"][0]["targets"]) == 40
    np.testing.assert_array_equal(per_frame.weights, np.eye(40))


def test_a_full_rank_animation_falls_back_to_one_target_per_frame():
    rest, faces = sheet(8)
    frames = rest + np.random.default_rng(5).normal(scale=2.0, size=(12,) + rest.shape)
    read, rows, grid, document = write_and_read(rest, faces, frames)
    assert len(document["meshes"][0]["primitives"][0]["targets"]) == 12
    assert "sparse" in document["accessors"][document["animations"][0]["samplers"][0]["output"]]
    np.testing.assert_array_equal(read.weights, np.eye(12))
    assert np.linalg.norm(read.frames - frames[:, rows], axis=2).max() <= grid.step * np.sqrt(3) / 2 * 1.0001


def test_the_basis_reproduces_an_exactly_low_rank_animation_and_bounds_its_search():
    rest, _ = sheet(10)
    base = np.rint(rest * 100)
    modes = np.random.default_rng(1).normal(scale=300, size=(2,) + rest.shape)
    amounts = np.random.default_rng(2).normal(size=(30, 2))
    frames = base + np.einsum("kj,jvc->kvc", amounts, modes)
    basis = low_rank_basis(base, frames, BASIS_TOLERANCE)
    assert basis.targets.shape == (2,) + rest.shape and np.abs(basis.targets).max() <= 32767
    assert 0 <= basis.weights.min() and basis.weights.max() <= 1 and np.ptp(basis.base, axis=0).max() <= 65535
    stored = basis.base - basis.base.min(axis=0)
    decoded = morphed_positions(stored, basis.weights, basis.targets)
    assert decoded.dtype == np.float32
    decoded = (decoded + basis.base.min(axis=0)) * basis.unit
    assert np.linalg.norm(decoded - frames, axis=2).max() <= BASIS_TOLERANCE
    many = np.repeat(frames[:1], MAX_BASIS_FRAMES + 1, axis=0)
    assert low_rank_basis(base, many, BASIS_TOLERANCE) is None


def test_unknown_targets_are_refused():
    rest, faces = sheet(4)
    grid = export_draco.animation_grid(rest[None], 10)
    with pytest.raises(ValueError, match="glb targets must be one of basis, frames, got 'pca'"):
        quantized_animation_glb(rest, faces, rest[None], ["a"], np.arange(16), grid, 24.0, "t", "test", targets="pca")
