"""Static obstacles as plain arrays: convex polygons and discs.

Kernels in :mod:`validity` take the packed arrays of :meth:`Obstacles.packed`. A general simple
polygon given by a user is split into convex pieces (triangles, by ear clipping) here, once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shapely.geometry import LinearRing


class ShapeError(ValueError):
    """A polygon or circle cannot be used as an obstacle."""


def signed_area(vertices: np.ndarray) -> float:
    """Shoelace area: positive for counter-clockwise vertices."""
    x, y = vertices[:, 0], vertices[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def is_convex(vertices: np.ndarray, tol: float = 1e-12) -> bool:
    """True for a counter-clockwise polygon with no reflex corner."""
    v = np.asarray(vertices, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    cross = e[:, 0] * np.roll(e, -1, axis=0)[:, 1] - e[:, 1] * np.roll(e, -1, axis=0)[:, 0]
    return bool(np.all(cross >= -tol))


def _point_in_triangle(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> bool:
    def cross(o: np.ndarray, u: np.ndarray, w: np.ndarray) -> float:
        return float((u[0] - o[0]) * (w[1] - o[1]) - (u[1] - o[1]) * (w[0] - o[0]))

    return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0


def ear_clip(vertices: np.ndarray) -> list[np.ndarray]:
    """Triangulate a simple counter-clockwise polygon; each triangle is CCW, shape (3, 2)."""
    v = [np.asarray(p, dtype=float) for p in vertices]
    index = list(range(len(v)))
    triangles = []
    guard = 0
    while len(index) > 3:
        guard += 1
        if guard > 10 * len(vertices) ** 2:
            raise ShapeError("polygon could not be triangulated: is it simple (no self-crossing)?")
        for k in range(len(index)):
            i0, i1, i2 = index[k - 1], index[k], index[(k + 1) % len(index)]
            a, b, c = v[i0], v[i1], v[i2]
            if (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) <= 1e-14:
                continue
            others = (v[j] for j in index if j not in (i0, i1, i2))
            if any(_point_in_triangle(p, a, b, c) for p in others):
                continue
            triangles.append(np.array([a, b, c]))
            index.pop(k)
            break
    triangles.append(np.array([v[i] for i in index]))
    return triangles


def convex_pieces(
    vertices: np.ndarray | list[list[float]], field: str = "polygon"
) -> list[np.ndarray]:
    """A simple polygon as a list of CCW convex pieces (itself if already convex)."""
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3:
        raise ShapeError(f"{field}: a polygon needs at least 3 points [x, y], got shape {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ShapeError(f"{field}: polygon coordinates must be finite numbers")
    area = signed_area(v)
    if abs(area) < 1e-12:
        raise ShapeError(f"{field}: polygon has zero area")
    if not LinearRing(v).is_simple:
        raise ShapeError(f"{field}: polygon is not simple (its edges cross)")
    if area < 0:
        v = v[::-1].copy()
    if is_convex(v):
        return [v]
    return ear_clip(v)


@dataclass(frozen=True)
class Obstacles:
    """Static obstacles: convex CCW polygons and discs ``(cx, cy, radius)``.

    ``labels`` names each polygon then each disc (e.g. ``'left wall (e)'``) for errors and plots.
    """

    polygons: tuple[np.ndarray, ...]
    circles: np.ndarray
    labels: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        circles = np.asarray(self.circles, dtype=float).reshape(-1, 3)
        object.__setattr__(self, "circles", circles)
        n = len(self.polygons) + len(circles)
        if self.labels and len(self.labels) != n:
            raise ShapeError(f"{len(self.labels)} labels for {n} obstacles")
        if not self.labels:
            names = [f"polygon {i}" for i in range(len(self.polygons))]
            names += [f"circle {i}" for i in range(len(circles))]
            object.__setattr__(self, "labels", tuple(names))

    def packed(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(vertices (P, K, 2), counts (P,), circles (C, 3))`` for the kernels.

        Polygons with fewer than K vertices repeat their last vertex (a zero-length edge).
        """
        k = max((len(p) for p in self.polygons), default=3)
        verts = np.zeros((len(self.polygons), k, 2))
        counts = np.zeros(len(self.polygons), dtype=np.int64)
        for i, p in enumerate(self.polygons):
            verts[i, : len(p)] = p
            verts[i, len(p) :] = p[-1]
            counts[i] = len(p)
        return verts, counts, np.ascontiguousarray(self.circles)
