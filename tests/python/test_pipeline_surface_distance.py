"""Point-to-triangle distances against a brute-force sampling of the triangle."""
import numpy as np

from meshik.posing.surface_distance import point_triangle_distance


def sampled_distance(point, a, b, c, steps=200):
    """The distance from `point` to a dense barycentric sampling of triangle abc (an upper bound)."""
    u, v = np.meshgrid(np.linspace(0, 1, steps), np.linspace(0, 1, steps))
    inside = u + v <= 1
    samples = a + np.outer(u[inside], b - a) + np.outer(v[inside], c - a)
    return np.linalg.norm(samples - point, axis=1).min()


def test_matches_sampling_in_every_region():
    rng = np.random.default_rng(7)
    points, a, b, c = (rng.normal(size=(300, 3)) for _ in range(4))
    c[:10] = a[:10] + 2.0 * (b[:10] - a[:10])  # degenerate (collinear) triangles
    distance = point_triangle_distance(points, a, b, c)
    for i in range(0, 300, 7):
        expected = sampled_distance(points[i], a[i], b[i], c[i])
        assert distance[i] <= expected + 1e-12
        assert distance[i] >= expected - 0.02 * np.linalg.norm(np.ptp([a[i], b[i], c[i]], axis=0))


def test_exact_cases():
    a, b, c = np.array([[0.0, 0, 0]]), np.array([[1.0, 0, 0]]), np.array([[0.0, 1, 0]])
    for point, expected in (([0.2, 0.2, 0.5], 0.5), ([2.0, 0, 0], 1.0), ([1.0, 1.0, 0], np.sqrt(0.5)), ([-1.0, -1.0, 0], np.sqrt(2))):
        np.testing.assert_allclose(point_triangle_distance(np.array([point]), a, b, c), [expected], atol=1e-12)
