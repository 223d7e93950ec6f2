"""Rigid motions of handle groups: rotation about an axis, and applying a motion to points."""
import numpy as np


def axis_angle_matrix(axis, degrees: float) -> np.ndarray:
    """3 by 3 rotation by `degrees` (right-handed) about `axis` (3 numbers, any non-zero length)."""
    axis = np.asarray(axis, dtype=float)
    axis = axis / np.linalg.norm(axis)
    angle = np.radians(degrees)
    cross = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle) * cross + (1.0 - np.cos(angle)) * (cross @ cross)


def is_rotation(matrix: np.ndarray, tolerance: float = 1e-5) -> bool:
    """Whether a 3 by 3 matrix is orthonormal with determinant +1, within `tolerance`."""
    return bool(np.allclose(matrix.T @ matrix, np.eye(3), atol=tolerance) and abs(np.linalg.det(matrix) - 1.0) <= tolerance)


def apply_rigid(points: np.ndarray, rotation: np.ndarray, translation: np.ndarray, center: np.ndarray) -> np.ndarray:
    """#P by 3 points moved by p -> rotation (p - center) + center + translation.

    points: #P by 3; rotation: 3 by 3; translation, center: 3 numbers.
    """
    return (points - center) @ rotation.T + center + translation
