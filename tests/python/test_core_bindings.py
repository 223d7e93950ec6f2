"""meshik._core from Python: array conversions, shape errors, InputError, the solve round trip on a
generated bending/twisting tube, warm starts, progress and cancellation, inverted triangles."""
import numpy as np
import pytest

import meshik


def make_tube(rings=13, segments=10):
    """A capped tube along z (132 vertices, 260 triangles) and three examples: bend, twist, bulge."""
    z = np.repeat(np.linspace(0.0, 4.0, rings), segments)
    angle = np.tile(np.arange(segments) * 2 * np.pi / segments, rings)
    rest = np.column_stack([0.5 * np.cos(angle), 0.5 * np.sin(angle), z])
    rest = np.vstack([rest, [0.0, 0.0, 0.0], [0.0, 0.0, 4.0]])
    bottom, top = rings * segments, rings * segments + 1
    faces = []
    for r in range(rings - 1):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            faces += [[a, b, b + segments], [a, b + segments, a + segments]]
    last = (rings - 1) * segments
    for s in range(segments):
        nxt = (s + 1) % segments
        faces += [[bottom, nxt, s], [top, last + s, last + nxt]]
    t = rest[:, 2] / 4.0
    bend_radius = 4.0 / (np.pi / 2)
    bend = rest.copy()
    bend[:, 1] = bend_radius - (bend_radius - rest[:, 1]) * np.cos(np.pi / 2 * t)
    bend[:, 2] = (bend_radius - rest[:, 1]) * np.sin(np.pi / 2 * t)
    twist = rest.copy()
    turn = 2.0 * t
    twist[:, 0] = rest[:, 0] * np.cos(turn) - rest[:, 1] * np.sin(turn)
    twist[:, 1] = rest[:, 0] * np.sin(turn) + rest[:, 1] * np.cos(turn)
    bulge = rest.copy()
    bulge[:, :2] *= (1.0 + 0.3 * np.sin(np.pi * t))[:, None]
    return rest, np.array(faces), [bend, twist, bulge]


HANDLES = [0, 5, 60, 65, 125, 129, 130, 131]


@pytest.fixture(scope="module")
def tube():
    return make_tube()


@pytest.mark.parametrize("space", ["nonlinear", "linear"])
def test_example_handles_give_the_example_and_its_unit_weight(tube, space):
    rest, faces, examples = tube
    solver = meshik.Solver(rest, faces, examples, HANDLES, feature_space=space)
    for i, pose in enumerate(examples):
        result = solver.solve(pose[HANDLES])
        assert result.vertices.shape == rest.shape and result.vertices.dtype == np.float64
        assert result.weights.shape == (3,)
        assert np.abs(result.vertices - pose).max() < 1e-6 * np.ptp(rest, axis=0).max()
        np.testing.assert_allclose(result.weights, np.eye(3)[i], atol=1e-6)
        assert result.converged and result.residual < 1e-12
        assert result.inverted_triangles.dtype == np.int64 and result.inverted_triangles.size == 0


def linear_space_inverted_triangles(rest, faces, examples, weights, posed):
    """Indices of the faces whose posed normal points away from the normal that the linear blend
    of the examples' deformation gradients, T(w) = I + sum_i w_i (T_i - I), gives the rest face
    (T_i = V~_i V^-1 with the fourth vertex of DESIGN.md section 2), computed here from scratch."""
    def frames(v):
        e1, e2 = v[faces[:, 1]] - v[faces[:, 0]], v[faces[:, 2]] - v[faces[:, 0]]
        n = np.cross(e1, e2)
        return np.stack([e1, e2, n / np.sqrt(np.linalg.norm(n, axis=1))[:, None]], axis=2)
    rest_frames = frames(rest)
    blended = np.eye(3) + sum(w * (frames(e) @ np.linalg.inv(rest_frames) - np.eye(3)) for w, e in zip(weights, examples))
    target = blended @ rest_frames
    target_normal = np.cross(target[:, :, 0], target[:, :, 1])
    posed_normal = np.cross(posed[faces[:, 1]] - posed[faces[:, 0]], posed[faces[:, 2]] - posed[faces[:, 0]])
    return np.nonzero(np.einsum("ij,ij->i", posed_normal, target_normal) < 0)[0]


@pytest.mark.parametrize("shift", [0.3, 1.0, 1.6])
def test_inverted_triangles_match_a_recomputation_in_the_linear_space(tube, shift):
    """Handle 0 (vertex 0) dragged along the tube past its neighbours: the faces reported turned
    over are exactly those a numpy recomputation finds, none for a small drag, some around the
    handle for a large one."""
    rest, faces, examples = tube
    solver = meshik.Solver(rest, faces, examples, HANDLES, feature_space="linear")
    targets = rest[HANDLES].copy()
    targets[0, 2] += shift
    result = solver.solve(targets)
    expected = linear_space_inverted_triangles(rest, faces, examples, result.weights, result.vertices)
    np.testing.assert_array_equal(result.inverted_triangles, expected)
    if shift < 0.5:
        assert result.inverted_triangles.size == 0
    else:
        assert np.isin(0, faces[result.inverted_triangles])


def test_float32_and_int32_inputs_are_converted(tube):
    rest, faces, examples = tube
    solver = meshik.Solver(rest.astype(np.float32), faces.astype(np.int32),
                           np.stack(examples).astype(np.float32), np.array(HANDLES, dtype=np.int32))
    result = solver.solve(examples[0][HANDLES].astype(np.float32))
    assert np.abs(result.vertices - examples[0].astype(np.float32)).max() < 1e-5
    assert solver.handles.tolist() == HANDLES and solver.num_examples == 3


def test_from_example_set_shares_the_features_and_blend_matches(tube):
    rest, faces, examples = tube
    example_set = meshik.ExampleSet(rest, faces, examples)
    assert (example_set.num_vertices, example_set.num_triangles, example_set.num_examples) == (132, 260, 3)
    solver = meshik.Solver.from_example_set(example_set, HANDLES, feature_space="linear")
    # The features are stored in single precision: the example to well within 1e-6 of the diagonal
    # (4.3), the rest exactly.
    np.testing.assert_allclose(example_set.blend([0, 1, 0]), examples[1], atol=1e-6)
    np.testing.assert_allclose(solver.blend([0, 0, 0]), rest, atol=1e-9)
    half = example_set.blend([0.5, 0, 0], feature_space="linear")
    assert half.shape == rest.shape


def test_warm_start_and_energies(tube):
    rest, faces, examples = tube
    solver = meshik.Solver(rest, faces, examples, HANDLES)
    targets = examples[0][HANDLES] * 1.1 + 0.2 * examples[1][HANDLES]
    cold = solver.solve(targets)
    assert np.all(np.diff(cold.energies) <= 0) and cold.energies[-1] == cold.residual
    warm = solver.solve(targets, initial_weights=cold.weights)
    assert warm.iterations <= 1 < cold.iterations
    np.testing.assert_allclose(warm.vertices, cold.vertices, atol=1e-8)


def test_soft_handles_stiff_approach_the_hard_pose_and_soft_keep_the_shape(tube):
    rest, faces, examples = tube
    targets = examples[0][HANDLES].copy()
    targets[0, 0] += 1.0  # out of the examples' reach: hard handles pull that vertex alone
    hard = meshik.Solver(rest, faces, examples, HANDLES).solve(targets)
    stiff = meshik.Solver(rest, faces, examples, HANDLES, handle_stiffness=1e6).solve(targets)
    soft = meshik.Solver(rest, faces, examples, HANDLES, handle_stiffness=1e-4).solve(targets)
    assert np.abs(stiff.vertices - hard.vertices).max() < 1e-4 * np.ptp(rest, axis=0).max()
    # Soft: example 0's shape moved as a whole, the handle short of its target.
    offset = soft.vertices - examples[0]
    assert np.abs(offset - offset.mean(axis=0)).max() < 0.01
    assert abs(soft.vertices[HANDLES[0], 0] - targets[0, 0]) > 0.5


@pytest.mark.parametrize("call, message", [
    (lambda t: meshik.Solver(t[0][:, :2], t[1], t[2], HANDLES), r"rest_vertices must have shape \(n, 3\), got \(132, 2\)"),
    (lambda t: meshik.Solver(t[0], t[1].astype(float), t[2], HANDLES), "faces must be an integer array"),
    (lambda t: meshik.Solver(t[0], t[1], [t[2][0], t[2][1][:5]], HANDLES), r"examples\[1\] must have shape \(132, 3\)"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], [0, 0]), r"handle 1 \(vertex 0\) repeats handle 0"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], [500]), r"handle 0 \(vertex 500\) is out of range"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], []), "no handles"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], HANDLES, feature_space="cubic"), "feature_space must be"),
    (lambda t: meshik.ExampleSet(t[0], t[1], t[2], feature_precision="half"), "feature_precision must be"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], HANDLES, handle_stiffness=-1.0), "handle_stiffness must be finite and >= 0"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], HANDLES).solve(np.zeros((3, 3))), r"targets must have shape \(8, 3\)"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], HANDLES).solve(t[0][HANDLES], [1.0]), r"initial_weights must have shape \(3,\)"),
    (lambda t: meshik.Solver(t[0], t[1], t[2], HANDLES).solve(t[0][HANDLES], [1.0, np.inf, 0.0]),
     r"initial_weights\[1\] \(the weight of example 1\) is inf, not a finite number"),
    (lambda t: meshik.ExampleSet(t[0], t[1], t[2]).blend([np.nan, 0, 0]), r"weights\[0\] \(the weight of example 0\) is nan, not a finite number"),
])
def test_bad_input_raises_input_error_naming_it(tube, call, message):
    with pytest.raises(meshik.InputError, match=message):
        call(tube)
    assert issubclass(meshik.InputError, ValueError)


def test_progress_is_reported_and_can_cancel_or_raise(tube):
    rest, faces, examples = tube
    stages = []
    solver = meshik.Solver(rest, faces, examples, HANDLES, progress=lambda f, s: stages.append((f, s)))
    assert stages and all(0.0 <= f <= 1.0 for f, _ in stages)
    targets = examples[0][HANDLES] * 1.1
    with pytest.raises(meshik.Cancelled):
        solver.solve(targets, progress=lambda f, s: False)

    def failing(fraction, stage):
        raise KeyError("from the callback")
    with pytest.raises(KeyError, match="from the callback"):
        solver.solve(targets, progress=failing)


def test_concurrent_solves_share_one_solver(tube):
    """solve() releases the GIL and is safe to call from several threads at once."""
    from concurrent.futures import ThreadPoolExecutor

    rest, faces, examples = tube
    solver = meshik.Solver(rest, faces, examples, HANDLES)
    targets = [examples[i % 3][HANDLES] * (1.0 + 0.05 * i) for i in range(8)]
    alone = [solver.solve(t).vertices for t in targets]
    with ThreadPoolExecutor(max_workers=4) as pool:
        together = list(pool.map(lambda t: solver.solve(t).vertices, targets))
    for a, b in zip(alone, together):
        np.testing.assert_array_equal(a, b)
