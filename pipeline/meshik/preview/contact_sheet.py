"""Flat-shaded preview pictures of meshes and a contact sheet of many frames (Pillow only).

A small painter's-algorithm renderer: triangles sorted back to front and filled with a
Lambert shade, so a person can look at posed frames without a GPU or a display.
"""
import math
from typing import Optional, Sequence

import numpy as np


def view_rotation(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """3 by 3 rotation taking world coordinates to camera coordinates (camera looks down -z)."""
    a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
    yaw = np.array([[math.cos(a), 0, -math.sin(a)], [0, 1, 0], [math.sin(a), 0, math.cos(a)]])
    pitch = np.array([[1, 0, 0], [0, math.cos(e), -math.sin(e)], [0, math.sin(e), math.cos(e)]])
    return pitch @ yaw


def render(vertices: np.ndarray, faces: np.ndarray, size: int = 256,
           bounds: Optional[tuple] = None, azimuth: float = 30.0, elevation: float = 20.0,
           color=(190, 160, 120), highlight: Optional[Sequence[int]] = None):
    """Renders one mesh to a `size` by `size` RGB PIL image.

    vertices:  #V by 3 positions; faces: #F by 3 vertex indices
    bounds:    (center 3-vector, radius) of the camera framing; computed from `vertices` when None
               (pass the same bounds for every frame of an animation so they line up)
    highlight: vertex indices drawn as red dots (handles)
    """
    from PIL import Image, ImageDraw

    rot = view_rotation(azimuth, elevation)
    if bounds is None:
        bounds = framing([vertices])
    center, radius = bounds
    cam = (np.asarray(vertices, dtype=float) - center) @ rot.T
    scale = 0.45 * size / radius
    xy = np.column_stack([size / 2 + cam[:, 0] * scale, size / 2 - cam[:, 1] * scale])
    tri = cam[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    lengths[lengths == 0] = 1.0
    light = np.array([0.3, 0.5, 0.8]) / np.linalg.norm([0.3, 0.5, 0.8])
    shade = np.abs(normals @ light) / lengths  # two-sided: open meshes show their back faces too
    order = np.argsort(tri[:, :, 2].mean(axis=1))  # far (most negative z) first
    image = Image.new("RGB", (size, size), (250, 250, 250))
    draw = ImageDraw.Draw(image)
    base = np.asarray(color, dtype=float)
    for f in order:
        fill = tuple(int(c) for c in base * (0.25 + 0.75 * shade[f]))
        draw.polygon([tuple(p) for p in xy[faces[f]]], fill=fill)
    for v in highlight if highlight is not None else ():
        x, y = xy[v]
        draw.ellipse([x - 2, y - 2, x + 2, y + 2], fill=(220, 30, 30))
    return image


def framing(vertex_sets: Sequence[np.ndarray]) -> tuple:
    """(center, radius) of the bounding box around every #V by 3 array in `vertex_sets`."""
    stacked = np.concatenate([np.asarray(v, dtype=float) for v in vertex_sets])
    lo, hi = stacked.min(axis=0), stacked.max(axis=0)
    return (lo + hi) / 2, max(float(np.linalg.norm(hi - lo)) / 2, 1e-12)


def contact_sheet(frames: Sequence[np.ndarray], faces: np.ndarray, labels: Sequence[str],
                  columns: int = 6, tile: int = 200, highlight: Optional[Sequence[int]] = None,
                  azimuth: float = 30.0, elevation: float = 20.0):
    """Renders every #V by 3 frame with one shared framing into a grid image with a label per tile.
    Returns the PIL image (columns wide, as many rows as needed)."""
    from PIL import Image, ImageDraw

    bounds = framing(frames)
    rows = math.ceil(len(frames) / columns)
    sheet = Image.new("RGB", (columns * tile, rows * tile), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    for i, (vertices, label) in enumerate(zip(frames, labels)):
        x, y = (i % columns) * tile, (i // columns) * tile
        sheet.paste(render(vertices, faces, tile, bounds, azimuth, elevation, highlight=highlight), (x, y))
        draw.text((x + 6, y + 4), label, fill=(40, 40, 40))
    return sheet
