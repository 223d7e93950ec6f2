"""The quantized / meshopt .glb writer and its meshoptimizer binding: the codecs round-trip, bad
input is refused with one clear line, the grid covers every frame, vertices no triangle uses are
kept, and the CLI's --glb / --position-bits / --glb-targets reach the file and report.json."""
import json

import numpy as np
import pytest

from meshik import _meshopt
from meshik.export import draco as export_draco
from meshik.export.glb_layout import rows_of_ids
from meshik.export.glb_reader import read_animation_glb
from meshik.cli import main
from meshik.export.glb_quantized import MAX_POSITION_BITS, quantized_animation_glb
from meshik.export.glb_container import split_glb


def canonical(indices: np.ndarray) -> np.ndarray:
    """#F by 3 triangles of a 3 #F index list, each rotated to start at its smallest corner (winding kept)."""
    triangles = indices.reshape(-1, 3)
    shift = np.argmin(triangles, axis=1)
    return np.stack([triangles[np.arange(len(triangles)), (shift + k) % 3] for k in range(3)], axis=1)


def test_meshopt_codecs_round_trip_and_refuse_bad_streams():
    rng = np.random.default_rng(3)
    rows = rng.integers(0, 256, size=(1000, 8), dtype=np.uint8)
    encoded = _meshopt.encode_vertex_buffer(rows)
    assert encoded[0] == 0xA0  # vertex codec version 0, as EXT_meshopt_compression requires
    np.testing.assert_array_equal(_meshopt.decode_vertex_buffer(encoded, 1000, 8), rows)
    indices = rng.integers(0, 50, size=300).astype(np.uint32)
    packed = _meshopt.encode_index_buffer(indices, 50)
    assert packed[0] == 0xE1  # index codec version 1
    # the same triangles with the same winding (the codec may rotate a triangle's corners)
    np.testing.assert_array_equal(canonical(_meshopt.decode_index_buffer(packed, 300)), canonical(indices))
    with pytest.raises(ValueError, match="index 2 is 60, past the 50 vertices"):
        _meshopt.encode_index_buffer(np.array([0, 1, 60], dtype=np.uint32), 50)
    with pytest.raises(ValueError, match="not a multiple of 4"):
        _meshopt.encode_vertex_buffer(rows[:, :6].copy())
    with pytest.raises(ValueError, match="malformed meshopt vertex stream"):
        _meshopt.decode_vertex_buffer(encoded[:20], 1000, 8)


def test_surface_walk_visits_every_vertex_stepping_to_the_nearest_neighbour():
    xs, ys = np.meshgrid(np.arange(6.0), np.arange(5.0))
    rest = np.c_[xs.ravel() * np.linspace(1.0, 2.0, 30), ys.ravel(), np.zeros(30)]  # uneven spacing
    faces = np.array([[r * 6 + c, r * 6 + c + 1, r * 6 + c + 6] for r in range(4) for c in range(5)] +
                     [[r * 6 + c + 1, r * 6 + c + 7, r * 6 + c + 6] for r in range(4) for c in range(5)])
    # a second component, and vertices 33 and 34 used by no triangle
    rest = np.vstack([rest, [[20.0, 0, 0], [21.0, 0, 0], [20.0, 1, 0], [50.0, 0, 0], [60.0, 0, 0]]])
    faces = np.vstack([faces, [[30, 31, 32]]]).astype(np.uint32)
    order = _meshopt.surface_walk(faces.reshape(-1), rest)
    assert sorted(order) == list(range(35)) and order[0] == faces[0, 0]
    assert list(order[-2:]) == [33, 34] and set(order[30:33]) == {30, 31, 32}
    neighbours = {v: set() for v in range(35)}
    for a, b, c in faces:
        neighbours[a] |= {b, c}
        neighbours[b] |= {a, c}
        neighbours[c] |= {a, b}
    seen = {order[0]}
    for before, vertex in zip(order[:29], order[1:30]):
        open_neighbours = neighbours[before] - seen
        if open_neighbours:  # a step, to the nearest of them; otherwise a back-up along the walk
            nearest = min(open_neighbours, key=lambda w: (np.sum((rest[w] - rest[before]) ** 2), w))  # ties: lower index
            assert vertex == nearest
        seen.add(vertex)
    np.testing.assert_array_equal(_meshopt.surface_walk(faces.reshape(-1), rest), order)  # deterministic
    with pytest.raises(ValueError, match="index 2 is 40, past the 35 vertices"):
        _meshopt.surface_walk(np.array([0, 1, 40], dtype=np.uint32), rest)


@pytest.fixture
def animation():
    """A 4 x 4 grid of vertices (vertex 16 used by no triangle), 3 frames moving it."""
    xs, ys = np.meshgrid(np.arange(4.0), np.arange(4.0))
    rest = np.c_[xs.ravel(), ys.ravel(), np.zeros(16)]
    rest = np.vstack([rest, [[9.0, 9.0, 1.0]]])
    faces = np.array([[r * 4 + c, r * 4 + c + 1, r * 4 + c + 4] for r in range(3) for c in range(3)])
    frames = np.stack([rest + [0, 0, 0.5 * k] + 0.1 * k * np.sin(rest) for k in range(3)])
    return rest, faces, frames, np.arange(17) * 5


@pytest.mark.parametrize("meshopt", [True, False])
def test_quantized_glb_reproduces_every_frame_on_the_grid(animation, meshopt):
    rest, faces, frames, ids = animation
    grid = export_draco.animation_grid(np.concatenate([frames, rest[None]]), 10)
    data = quantized_animation_glb(rest, faces, frames, ["a", "b", "c"], ids, grid, 30.0, "grid", "test", meshopt=meshopt)
    read = read_animation_glb(data)
    rows = rows_of_ids(ids, read.vertex_ids)
    assert sorted(read.vertex_ids) == sorted(ids) and read.frame_names == ("a", "b", "c")
    assert np.linalg.norm(read.frames - frames[:, rows], axis=2).max() <= grid.step * np.sqrt(3) / 2 * 1.0001
    # morph weights inside [0, 1] (the basis moved to its weights' corner), and the default ones show frame 0
    assert 0 <= read.weights.min() and read.weights.max() <= 1
    np.testing.assert_array_equal(read.default_weights, read.weights[0])
    # the triangles are the same, with the same winding (reordered for the vertex cache)
    assert sorted(map(tuple, canonical(ids[rows][read.faces].ravel()))) == sorted(map(tuple, canonical(ids[faces].ravel())))
    document, _ = split_glb(data)
    compressed = [v for v in document["bufferViews"] if "extensions" in v]
    assert len(compressed) == (len(document["bufferViews"]) if meshopt else 0)


def test_quantized_glb_refuses_bad_input(animation):
    rest, faces, frames, ids = animation
    grid = export_draco.animation_grid(frames, MAX_POSITION_BITS + 1)
    with pytest.raises(ValueError, match=f"position bits must be between 1 and {MAX_POSITION_BITS}"):
        quantized_animation_glb(rest, faces, frames, ["a", "b", "c"], ids, grid, 30.0, "x", "t")
    grid = export_draco.animation_grid(frames, 12)
    broken = frames.copy()
    broken[1, 3, 0] = np.nan
    with pytest.raises(ValueError, match="not all finite"):
        quantized_animation_glb(rest, faces, broken, ["a", "b", "c"], ids, grid, 30.0, "x", "t")
    with pytest.raises(ValueError, match="fit a glTF float attribute"):
        quantized_animation_glb(rest, faces, frames, ["a", "b", "c"], ids + 2 ** 24, grid, 30.0, "x", "t")


def test_cli_glb_options_reach_the_file_and_the_report(samples_dir, tmp_path, capsys):
    constraints = samples_dir / "bar" / "animation.json"
    assert main(["pose", str(constraints), "--out", str(tmp_path / "q"), "--glb", "quantized", "--position-bits", "12",
                 "-q"]) == 0
    report = json.loads((tmp_path / "q" / "report.json").read_text())
    entry = report["compressed_outputs"]["animation.glb"]
    assert entry["variant"] == "quantized" and entry["position_bits"] == 12
    document, _ = split_glb((tmp_path / "q" / "animation.glb").read_bytes())
    assert document["extensionsRequired"] == ["KHR_mesh_quantization"]
    assert 0 < document["nodes"][0]["scale"][0] <= entry["grid_step"]  # the basis' node unit: the grid's or finer
    assert entry["morph_targets"] < report["frame_count"]  # the default basis: the bar's frames are low-rank
    assert entry["readers"]["needs"] == ["KHR_mesh_quantization"] and "Blender 5.0.1" in entry["readers"]["opens_in"]
    assert main(["pose", str(constraints), "--out", str(tmp_path / "f"), "--glb-targets", "frames", "-q"]) == 0
    report = json.loads((tmp_path / "f" / "report.json").read_text())
    entry = report["compressed_outputs"]["animation.glb"]
    assert entry["morph_targets"] == report["frame_count"] and entry["variant"] == "quantized"  # the default variant
    document, _ = split_glb((tmp_path / "f" / "animation.glb").read_bytes())
    assert document["nodes"][0]["scale"][0] == pytest.approx(entry["grid_step"])
    assert main(["pose", str(constraints), "--out", str(tmp_path / "m"), "--glb", "meshopt", "-q"]) == 0
    readers = json.loads((tmp_path / "m" / "report.json").read_text())["compressed_outputs"]["animation.glb"]["readers"]
    assert readers["needs"][-1] == "EXT_meshopt_compression" and readers["refused_by"][0].startswith("Blender 5.0.1")
    assert main(["info", str(tmp_path / "m" / "animation.glb")]) == 0
    assert "EXT_meshopt_compression" in capsys.readouterr().out
    assert main(["pose", str(constraints), "--out", str(tmp_path / "bad"), "--position-bits", "16", "-q"]) == 1
    assert "position bits must be between 1 and 15, got 16" in capsys.readouterr().err
    assert main(["pose", str(constraints), "--out", str(tmp_path / "bad"), "--position-bits", "3", "-q"]) == 1
    assert "raise --position-bits" in capsys.readouterr().err  # a grid that would blur every frame
    assert main(["pose", str(constraints), "--out", str(tmp_path / "bad"), "--glb", "gzip"]) == 2
    assert main(["pose", str(constraints), "--out", str(tmp_path / "bad"), "--glb-targets", "pca"]) == 2
    assert not (tmp_path / "bad").exists()
