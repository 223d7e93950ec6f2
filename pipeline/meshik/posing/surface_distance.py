"""Distances from points to triangles, vectorised over (point, triangle) pairs."""
import numpy as np


def point_triangle_distance(points: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Distance from each point to its triangle: #P distances for #P points and #P triangles (a, b, c).

    points, a, b, c: #P by 3. Degenerate triangles are handled (the distance to their edges).
    Uses the Voronoi regions of the triangle's vertices, edges and face (closest-point test).
    """
    ab, ac, ap = b - a, c - a, points - a
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    bp = points - b
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    cp = points - c
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        # inside the face: barycentric coordinates (u, v, w) from the signed areas
        denominator = va + vb + vc
        v = vb / denominator
        w = vc / denominator
        closest = a + ab * v[:, None] + ac * w[:, None]
        inside = (va >= 0) & (vb >= 0) & (vc >= 0) & (denominator > 0)
    distance = np.where(inside, np.linalg.norm(points - closest, axis=1), np.inf)
    # outside the face (or degenerate): the nearest of the three edges
    for start, end in ((a, b), (b, c), (c, a)):
        distance = np.minimum(distance, point_segment_distance(points, start, end))
    return distance


def point_segment_distance(points: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Distance from each point to its segment: #P distances; points, start, end #P by 3."""
    direction = end - start
    length2 = _dot(direction, direction)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(length2 > 0, _dot(points - start, direction) / length2, 0.0)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(points - (start + direction * t[:, None]), axis=1)


def _dot(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Row-wise dot products of two #P by 3 arrays: #P values."""
    return np.einsum("ij,ij->i", x, y)
