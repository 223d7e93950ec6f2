"""pose_job end to end on a small tube: every output decodes to the solver's own result (within the
Draco quantisation step), the report says what happened, simplified jobs keep their handles."""
import json

import numpy as np
import pytest
import trimesh

import meshik
from meshik.inputs import constraints
from meshik.export import draco as export_draco
from meshik.export.glb_reader import read_animation_glb
from meshik.inputs.meshio import load_example_set, load_mesh
from meshik.pipeline import pose_job
from meshik.posing.simplify import simplify_animation
from pipeline_clients import decode_with_draco_decoder, validate_and_check_no_errors
from pipeline_meshes import tube_constraints, write_constraints, write_tube_set


@pytest.fixture(scope="module")
def shot(tmp_path_factory):
    """A 160-vertex tube set and a 5-frame constraint file bending its top ring."""
    folder = tmp_path_factory.mktemp("shot")
    tube_set = write_tube_set(folder, rings=16, segments=10)
    path = write_constraints(folder / "bend.json", tube_constraints(tube_set, frames=5))
    return {"set": tube_set, "path": path, "folder": folder}


def solver_reference(path, feature_space="nonlinear"):
    """The core's own result for every frame (same handles, targets and warm start as the pipeline)."""
    constraint_set = constraints.load(path)
    meshes = load_example_set(constraint_set.rest, constraint_set.examples)
    resolved = constraints.resolve(constraint_set, meshes.rest)
    solver = meshik.Solver(meshes.rest, meshes.faces, list(meshes.examples), resolved.handles, feature_space=feature_space)
    frames, weights = [], None
    for targets in resolved.targets:
        result = solver.solve(targets, initial_weights=weights)
        weights = np.asarray(result.weights)
        frames.append(np.asarray(result.vertices))
    return np.stack(frames), resolved


def test_outputs_decode_to_the_solver_result(shot, tmp_path):
    """DracoPy and Google's draco_decoder decode every .drc, the glTF Validator and trimesh accept
    the .glb, and all of them give back the solver's own positions."""
    out = tmp_path / "out"
    # the Draco .glb, which trimesh reads (no meshopt decoder there); test_glb_clients reads the others
    report = pose_job(shot["path"], out, formats=("drc", "glb", "ply"), glb="draco", quiet=True)
    expected, resolved = solver_reference(shot["path"])
    step = report["quantization"]["step"]
    assert report["frame_count"] == 5 and not report["skipped"]
    assert step == pytest.approx(report["quantization"]["range"] / (2 ** 14 - 1))
    for k, name in enumerate(resolved.frame_names):
        drc = out / "frames" / f"{name}.drc"
        decoded = export_draco.decode(drc.read_bytes())
        assert decoded.method == export_draco.EDGEBREAKER
        assert np.abs(decoded.vertices - expected[k][decoded.vertex_ids]).max() <= step
        by_google, google_faces = decode_with_draco_decoder(drc, tmp_path)
        assert np.abs(by_google - expected[k][decoded.vertex_ids]).max() <= step
        np.testing.assert_array_equal(google_faces, decoded.faces)
        vertices, faces = load_mesh(out / "frames" / f"{name}.ply")
        np.testing.assert_allclose(vertices, expected[k], atol=1e-9)
        np.testing.assert_array_equal(faces, shot["set"]["faces"])
    validate_and_check_no_errors(out / "bend.glb")
    (mesh,) = trimesh.load(out / "bend.glb").geometry.values()  # structure only: trimesh has no Draco decoder
    assert mesh.vertices.shape == expected[0].shape
    animation = read_animation_glb((out / "bend.glb").read_bytes())
    assert animation.frame_names == resolved.frame_names
    np.testing.assert_allclose(animation.frames, expected[:, animation.vertex_ids], atol=1e-5)


def test_report_records_fit_weights_timings_and_sizes(shot, tmp_path):
    out = tmp_path / "out"
    report = pose_job(shot["path"], out, formats=("drc", "glb"), feature_space="linear", quiet=True)
    on_disk = json.loads((out / "report.json").read_text())
    assert on_disk == {k: v for k, v in report.items() if k != "skipped"}
    assert report["solver"]["feature_space"] == "linear" and report["solver"]["handle_vertices"] == 20
    assert report["handle_fit_error"]["max"] < 1e-8  # handles are hard constraints
    first, *others = report["frames"]
    np.testing.assert_allclose(first["weights"], [0.0, 0.0], atol=1e-9)  # frame 1 asks for the rest pose
    for frame in others:  # in the linear space the solver's linear-space start is the optimum already
        assert len(frame["weights"]) == 2 and frame["converged"] and frame["solve_seconds"] > 0
    # the bend grows frame by frame: so does the weight of the example bent the same way (about y)
    first_example = [frame["weights"][0] for frame in report["frames"]]
    assert first_example == sorted(first_example) and first_example[-1] > 0.5
    assert set(report["timings"]) >= {"load", "simplify", "pose", "export", "total", "precompute", "solve_mean"}
    inverted = [frame["inverted_triangles"] for frame in report["frames"]]
    assert all(isinstance(count, int) and count >= 0 for count in inverted)
    assert report["inverted_triangles"] == {"max": max(inverted), "frames": sum(count > 0 for count in inverted)}
    for name, size in report["outputs"].items():
        assert (out / name).stat().st_size == size
    assert pose_job(shot["path"], out, formats=("drc", "glb"), feature_space="linear", quiet=True)["skipped"]
    assert not pose_job(shot["path"], out, formats=("drc", "glb"), quiet=True)["skipped"]  # other options


@pytest.mark.parametrize("simplifier", ["fast", "openmesh"])
def test_simplified_job_keeps_handles_and_original_ids(shot, tmp_path, simplifier):
    out = tmp_path / "out"
    report = pose_job(shot["path"], out, simplify=120, simplifier=simplifier, formats=("drc", "obj"), quiet=True)
    meshes = load_example_set(shot["set"]["rest"], shot["set"]["examples"])
    handles = np.array(shot["set"]["bottom"] + shot["set"]["top"])
    simplified, _ = simplify_animation(meshes, solver_reference(shot["path"])[0], 120, handles, simplifier)
    assert report["simplification"]["triangles"] == len(simplified.meshes.faces) <= 120
    decoded = export_draco.decode((out / "frames" / "0005.drc").read_bytes())
    assert sorted(decoded.vertex_ids) == sorted(simplified.source_vertex)
    ids = np.loadtxt(out / "vertex_ids.txt", dtype=int)
    np.testing.assert_array_equal(ids, simplified.source_vertex)
    # both decimators lock the handles: none merged, each on its target
    assert report["handle_fit_error"]["max"] < 1e-8 and report["simplification"]["merged_handle_vertices"] == 0
