"""Exporters checked by real clients: Google's draco_decoder (Debian `draco`) and DracoPy decode the
.drc files, the Khronos glTF Validator and trimesh / pygltflib read the .glb."""
import numpy as np
import pytest

from meshik.export import draco as export_draco
from meshik.export import glb_draco
from meshik.export.glb_reader import read_animation_glb
from pipeline_clients import decode_with_draco_decoder, validate_and_check_no_errors
from pipeline_meshes import bend, tube

@pytest.fixture(scope="module")
def animation():
    """A tube bending over 5 frames, its rest pose and per-vertex ids (not 0..n-1, to catch mix-ups)."""
    vertices, faces = tube(rings=12, segments=10)
    frames = np.stack([bend(vertices, angle) for angle in np.linspace(0, 120, 5)])
    frames[:, :10] = vertices[:10]  # the bottom ring never moves
    return {"rest": vertices, "faces": faces, "frames": frames, "ids": np.arange(len(vertices)) * 7 + 3}


def test_drc_decoded_by_draco_decoder_and_dracopy(animation, tmp_path):
    grid = export_draco.animation_grid(animation["frames"], bits=14)
    orders = []
    for k, frame in enumerate(animation["frames"]):
        path = tmp_path / f"{k}.drc"
        path.write_bytes(export_draco.encode_frame(frame, animation["faces"], animation["ids"], grid))
        decoded = export_draco.decode(path.read_bytes())
        assert decoded.method == export_draco.EDGEBREAKER
        rows = (decoded.vertex_ids - 3) // 7
        np.testing.assert_array_equal(np.sort(rows), np.arange(len(frame)))
        assert np.abs(decoded.vertices - frame[rows]).max() <= grid.step
        # same connectivity up to the vertex order: the triangles name the same original vertices
        original = {tuple(sorted(t)) for t in animation["faces"].tolist()}
        assert {tuple(sorted(t)) for t in rows[decoded.faces].tolist()} == original
        # Google's decoder reads the file too and agrees with DracoPy vertex for vertex
        vertices, faces = decode_with_draco_decoder(path, tmp_path)
        np.testing.assert_allclose(vertices, decoded.vertices, atol=1e-6)
        np.testing.assert_array_equal(faces, decoded.faces)
        orders.append(decoded.vertex_ids)
    # edgebreaker orders vertices by connectivity only: every frame has the same order
    for order in orders[1:]:
        np.testing.assert_array_equal(order, orders[0])


def test_one_grid_keeps_static_vertices_still(animation):
    grid = export_draco.animation_grid(animation["frames"], bits=11)
    decoded = [export_draco.decode(export_draco.encode_frame(f, animation["faces"], animation["ids"], grid))
               for f in animation["frames"]]
    static = np.isin((decoded[0].vertex_ids - 3) // 7, np.arange(10))
    for other in decoded[1:]:
        np.testing.assert_array_equal(other.vertices[static], decoded[0].vertices[static])
    # per-frame grids (Draco's default) would move them: the shared grid is what prevents it
    own = [export_draco.decode(export_draco.encode_frame(f, animation["faces"], animation["ids"],
                                                         export_draco.animation_grid(f, bits=11)))
           for f in animation["frames"]]
    assert any(np.abs(o.vertices[static] - own[0].vertices[static]).max() > 0 for o in own[1:])


def test_glb_valid_and_frames_reproduced(animation, tmp_path):
    grid = export_draco.animation_grid(np.concatenate([animation["frames"], animation["rest"][None]]))
    names = [f"f{k}" for k in range(len(animation["frames"]))]
    data = glb_draco.animation_glb(animation["rest"], animation["faces"], animation["frames"], names, animation["ids"],
                                     grid, fps=24.0, name="tube", generator="test")
    path = tmp_path / "tube.glb"
    path.write_bytes(data)
    issues = validate_and_check_no_errors(path)
    assert {m["code"] for m in issues["messages"]} <= {"UNSUPPORTED_EXTENSION", "UNUSED_OBJECT"}

    read = read_animation_glb(data)
    rows = (read.vertex_ids - 3) // 7
    assert read.frame_names == tuple(names)
    np.testing.assert_allclose(read.times, np.arange(5) / 24.0, rtol=1e-6)
    assert np.abs(read.rest - animation["rest"][rows]).max() <= grid.step
    scale = np.abs(animation["frames"]).max()
    np.testing.assert_allclose(read.frames, animation["frames"][:, rows], atol=4 * np.finfo(np.float32).eps * scale)

    import pygltflib
    import trimesh

    gltf = pygltflib.GLTF2().load(str(path))
    assert gltf.extensionsRequired == [glb_draco.DRACO_EXTENSION]
    assert len(gltf.meshes[0].primitives[0].targets) == 5 and len(gltf.animations) == 1
    # trimesh has no Draco decoder: it loads the structure (counts from the accessors), not positions
    scene = trimesh.load(path)
    (mesh,) = scene.geometry.values()
    assert mesh.vertices.shape == animation["rest"].shape and len(mesh.faces) == len(animation["faces"])


def test_glb_rejects_ids_a_float_cannot_hold(animation):
    grid = export_draco.animation_grid(animation["frames"])
    with pytest.raises(ValueError, match="fit a glTF float attribute"):
        glb_draco.animation_glb(animation["rest"], animation["faces"], animation["frames"], ["a"] * 5,
                                  animation["ids"] + 2 ** 24, grid, 24.0, "tube", "test")
