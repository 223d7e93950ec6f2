"""The example-set precompute and the solve on several threads give the same bits as on one (issue 13)."""
import numpy as np
import pytest

import meshik
from meshik.inputs.meshio import load_example_set


@pytest.fixture(scope="module")
def limb(samples_dir):
    folder = samples_dir / "limb"
    return load_example_set(folder / "rest.obj", sorted(folder.glob("example_*.obj")))


def test_any_thread_count_gives_identical_features(limb):
    weights = np.linspace(0.2, -0.1, len(limb.examples))
    handles = [0, len(limb.rest) // 2, len(limb.rest) - 1]
    targets = limb.rest[handles] + [[0, 0, 0], [0.1, 0.2, 0], [0.3, 0, 0.1]]
    results = {}
    for threads in (1, 2, 3, 4, None):
        example_set = meshik.ExampleSet(limb.rest, limb.faces, list(limb.examples), threads=threads)
        solver = meshik.Solver.from_example_set(example_set, handles)
        result = solver.solve(targets)
        results[threads] = (example_set.blend(weights), example_set.blend(weights, feature_space="linear"),
                            result.vertices, result.weights)
    for threads, arrays in results.items():
        for one, other in zip(results[1], arrays):
            assert np.array_equal(one, other), f"threads={threads} differs from threads=1"


@pytest.mark.parametrize("space", ["nonlinear", "linear"])
def test_any_thread_count_gives_the_same_pose(limb, space):
    example_set = meshik.ExampleSet(limb.rest, limb.faces, list(limb.examples), threads=1)
    handles = [0, len(limb.rest) // 3, len(limb.rest) - 1]
    targets = limb.rest[handles] + [[0, 0, 0], [0.3, 0.4, -0.2], [0.6, -0.3, 0.2]]
    rest_weights = np.zeros(len(limb.examples))
    results = {}
    for threads in (1, 2, 3, None):
        solver = meshik.Solver.from_example_set(example_set, handles, feature_space=space, threads=threads)
        results[threads] = [solver.solve(targets), solver.solve(targets, initial_weights=rest_weights)]
    assert results[1][1].iterations >= 1
    for threads, poses in results.items():
        for one, other in zip(results[1], poses):
            assert np.array_equal(one.vertices, other.vertices), f"threads={threads} differs from threads=1"
            assert np.array_equal(one.weights, other.weights) and np.array_equal(one.energies, other.energies)


@pytest.mark.parametrize("threads", [0, -1, 5000])
def test_a_bad_thread_count_is_refused(limb, threads):
    with pytest.raises(meshik.InputError, match="threads"):
        meshik.ExampleSet(limb.rest, limb.faces, list(limb.examples), threads=threads)
    with pytest.raises(meshik.InputError, match="threads"):
        meshik.Solver.from_example_set(meshik.ExampleSet(limb.rest, limb.faces, list(limb.examples)), [0],
                                       threads=threads)


def test_pose_outputs_are_the_same_bytes_for_any_thread_count(samples_dir, tmp_path):
    from meshik.cli import main

    outputs = {}
    for threads in ("1", "2"):
        out = tmp_path / threads
        assert main(["pose", str(samples_dir / "limb" / "animation.json"), "--out", str(out), "--quiet",
                     "--threads", threads, "--format", "drc,ply"]) == 0
        outputs[threads] = {p.relative_to(out): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()
                            and p.name != "report.json"}
    assert outputs["1"] == outputs["2"] and len(outputs["1"]) > 10
