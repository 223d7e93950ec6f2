"""Thread counts from a hostile caller (issue 23): the Python API and the plugin in pymeshlab.

Before: threads=2**70 or 2.5 in the API raised std::bad_cast; the plugin's threads=2**31-1 made
libgomp try to allocate 481 GB and the host process exited. Now every thread count outside 1..4096
(0 too in the plugin: all cores) is refused with the parameter's name, and the host survives.
"""
import numpy as np
import pytest

import meshik
from pipeline_meshes import grid
from plugin_helpers import POSE, apply_refused, mesh_set, select_vertices

BAD_THREADS = {"2**70": 2 ** 70, "2**31-1": 2 ** 31 - 1, "4097": 4097, "2.5": 2.5, "True": True, "'4'": "4",
               "-1": -1, "0": 0, "float 4.0": 4.0, "list": [2]}


@pytest.fixture(scope="module")
def example_set():
    """A 5x5 grid with one bent example: (rest, faces, examples, ExampleSet)."""
    vertices, faces = grid(5, 4.0)
    posed = vertices.copy()
    posed[:, 2] = 0.1 * vertices[:, 0] ** 2
    return vertices, faces, [posed], meshik.ExampleSet(vertices, faces, [posed])


@pytest.mark.parametrize("value", sorted(BAD_THREADS))
def test_example_set_threads(example_set, value):
    rest, faces, examples, _ = example_set
    with pytest.raises(meshik.InputError, match=r"^threads must be None \(all cores\) or an integer from 1 to 4096, "
                                                r"got [^\n]+$"):
        meshik.ExampleSet(rest, faces, examples, threads=BAD_THREADS[value])


@pytest.mark.parametrize("value", sorted(BAD_THREADS))
def test_solver_threads(example_set, value):
    rest, faces, examples, features = example_set
    with pytest.raises(meshik.InputError, match=r"^threads must be None \(all cores\) or an integer from 1 to 4096"):
        meshik.Solver.from_example_set(features, np.array([0, 24]), threads=BAD_THREADS[value])


@pytest.mark.parametrize("value", [2 ** 31 - 1, 4097, 100_000, -1])
def test_plugin_threads_capped_with_the_parameters_name(example_set, value):
    rest, faces, examples, _ = example_set
    ms = mesh_set(rest, faces, examples)
    select_vertices(ms, [0, 24])
    message = apply_refused(ms, POSE, targetsource="Handle transform", threads=value)
    assert "threads: expected 0 (all cores) or a count from 1 to 4096" in message, message
    ms.set_current_mesh(0)
    select_vertices(ms, [0, 24])
    assert ms.apply_filter(POSE, targetsource="Handle transform", threads=2)["layer_id"] > 0  # the host survives
