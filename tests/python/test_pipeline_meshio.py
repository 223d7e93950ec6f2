"""Mesh I/O through pymeshlab: formats, topology checks with messages naming file and triangle."""
import numpy as np
import pytest

from meshik.errors import MeshFileError, OutputError
from meshik.inputs.meshio import load_example_set, load_mesh, save_mesh, saveable_format
from pipeline_meshes import bend, tube, write_obj, write_tube_set


@pytest.mark.parametrize("extension", ["ply", "obj", "off", "stl"])
def test_save_and_load_round_trip(tmp_path, extension):
    vertices, faces = tube(rings=4, segments=5)
    path = tmp_path / f"tube.{extension}"
    save_mesh(path, vertices, faces)
    loaded, loaded_faces = load_mesh(path)
    if extension == "stl":  # STL stores float32 triangle soup; MeshLab re-merges the corners
        assert len(loaded) == len(vertices) and len(loaded_faces) == len(faces)
        return
    np.testing.assert_allclose(loaded, vertices, atol=1e-12)
    np.testing.assert_array_equal(loaded_faces, faces)


def test_saved_files_hold_positions_and_triangles_only(tmp_path):
    vertices, faces = tube(rings=3, segments=4)
    save_mesh(tmp_path / "plain.obj", vertices, faces)
    text = (tmp_path / "plain.obj").read_text()
    assert "vn " not in text and all(len(line.split()) == 4 for line in text.splitlines() if line.startswith("v "))


def test_example_set_loads_every_pose(tmp_path):
    tube_set = write_tube_set(tmp_path, rings=5, segments=6)
    meshes = load_example_set(tube_set["rest"], tube_set["examples"])
    np.testing.assert_allclose(meshes.rest, tube_set["vertices"], atol=1e-8)
    np.testing.assert_array_equal(meshes.faces, tube_set["faces"])
    for loaded, expected in zip(meshes.examples, tube_set["example_vertices"]):
        np.testing.assert_allclose(loaded, expected, atol=1e-8)


def test_example_with_a_different_triangle_is_named(tmp_path):
    tube_set = write_tube_set(tmp_path, rings=5, segments=6)
    faces = tube_set["faces"].copy()
    faces[17] = faces[17][[0, 2, 1]]
    write_obj(tmp_path / "example_2.obj", bend(tube_set["vertices"], 30), faces)
    with pytest.raises(MeshFileError) as raised:
        load_example_set(tube_set["rest"], tube_set["examples"])
    message = str(raised.value)
    assert message.startswith(str(tmp_path / "example_2.obj")) and "triangle 17" in message
    assert str(tube_set["rest"]) in message


def test_example_with_other_vertex_count_is_named(tmp_path):
    tube_set = write_tube_set(tmp_path, rings=5, segments=6)
    vertices, faces = tube(rings=6, segments=6)
    write_obj(tmp_path / "example_1.obj", vertices, faces)
    with pytest.raises(MeshFileError, match=r"example_1.obj: has 36 vertices but the rest mesh .* has 30"):
        load_example_set(tube_set["rest"], tube_set["examples"])


def test_missing_and_unreadable_files(tmp_path):
    with pytest.raises(MeshFileError, match="none.obj: mesh file not found"):
        load_mesh(tmp_path / "none.obj")
    (tmp_path / "broken.obj").write_text("v 1 2\nf 1 2 3\n")
    with pytest.raises(MeshFileError, match="broken.obj: line 1: vertex coordinates are not three numbers: 'v 1 2'"):
        load_mesh(tmp_path / "broken.obj")
    (tmp_path / "broken.ply").write_text("ply\nformat nonsense 1.0\nend_header\n")
    with pytest.raises(MeshFileError, match="broken.ply: cannot read the mesh"):
        load_mesh(tmp_path / "broken.ply")
    (tmp_path / "points.obj").write_text("v 0 0 0\nv 1 0 0\n")
    with pytest.raises(MeshFileError, match="points.obj: the mesh has no triangles"):
        load_mesh(tmp_path / "points.obj")



def test_example_with_a_nan_vertex_is_named(tmp_path):
    tube_set = write_tube_set(tmp_path, rings=5, segments=6)
    text = tube_set["examples"][1].read_text().splitlines()
    text[4] = "v 0.5 nan 1.0"
    tube_set["examples"][1].write_text("\n".join(text) + "\n")
    # refused with its line before MeshLab's reader could drop the vertex and shift every later index
    with pytest.raises(MeshFileError, match=r"example_2.obj: line 5: the coordinate nan is not a finite number"):
        load_example_set(tube_set["rest"], tube_set["examples"])


def test_unknown_output_format(tmp_path):
    assert saveable_format("ply") and saveable_format("obj") and not saveable_format("glb")
    with pytest.raises(OutputError, match="cannot write the mesh"):
        save_mesh(tmp_path / "x.unknownformat", *tube(rings=3, segments=3))
