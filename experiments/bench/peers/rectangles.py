"""A scene's polygons as rectangles (centre, half sizes, angle), for engines whose planar
analogue of a polygon is a box primitive (MuJoCo's box geom)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Rectangle:
    """Centre (x, y), half sizes along its first edge and across it, and that edge's angle
    (rad, counter-clockwise from +x)."""

    centre: tuple[float, float]
    half_length: float
    half_width: float
    angle: float


def rectangle_of(vertices: np.ndarray, tolerance: float = 1e-9) -> Rectangle:
    """The rectangle with these four corners (either orientation); ValueError when they are
    not a rectangle (four corners, right angles within ``tolerance``)."""
    v = np.asarray(vertices, dtype=float)
    if v.shape != (4, 2):
        raise ValueError(f"obstacle with {len(v)} corners: only rectangles can be boxes")
    edges = np.roll(v, -1, axis=0) - v
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    for k in range(4):
        cosine = float(edges[k] @ edges[(k + 1) % 4]) / (lengths[k] * lengths[(k + 1) % 4])
        if abs(cosine) > tolerance:
            raise ValueError(f"obstacle {v.tolist()} is not a rectangle (corner {k} not square)")
    centre = v.mean(axis=0)
    return Rectangle(
        (float(centre[0]), float(centre[1])),
        0.5 * float(lengths[0]),
        0.5 * float(lengths[1]),
        math.atan2(float(edges[0, 1]), float(edges[0, 0])),
    )
