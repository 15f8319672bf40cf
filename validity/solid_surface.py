"""The real surface of obstacles built from overlapping convex pieces, decided once per scene.

Obstacles are convex polygons and discs that may overlap or share edges: mitred wall segments,
the triangles of an ear-clipped polygon, the pin's finger inside the cavity wall, a post standing
on a floor. A part touches only the boundary of their union. An edge of one piece can be
covered by another piece along all of its length (a seam), along none of it (a surface), or
along part of it (a post on a floor covers the middle of the floor's top edge). Contact
features must cover every point of the union's boundary and no point strictly inside the union:
a lost stretch of surface lets the part through the wall, a seam taken for surface pushes the
part sideways ("ghost contacts").

:func:`split_at_cover` splits every polygon edge at the points where another piece starts or
stops covering it (exact: each convex piece covers one interval of the edge line, each disc
one interval too), so that each sub-edge is covered along its whole length or nowhere; the
inserted vertices are collinear, so every piece stays convex. The contact kernel then decides
"surface or seam" per sub-edge, and a vertex inserted where cover begins is a concave corner of
the union (the free space there spans less than a half plane), which no part can touch with a
face: it is no contact corner. The split is compiled (:mod:`validity.cover_kernel`): a made
feeder's surface is decided once per verdict trial.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from validity.contact_kernel import corner_vertices
from validity.cover_kernel import edge_cover, piece_boxes, split_kernel


@dataclass(frozen=True)
class SolidSurface:
    """The obstacle polygons with edges split where cover changes, and what is real surface.

    ``verts (P, K, 2)``, ``counts (P,)`` as :meth:`feeders.shapes.Obstacles.packed` (padding
    repeats the last vertex; ``(0, 3, 2)`` when there are none, as numba needs a typed array);
    ``surface (P, K)`` True for sub-edges that face free space along
    their whole length, False for seams; ``corners (P, K)`` True for vertices a part can touch
    (neither a flat joint between two pieces nor a concave corner where cover begins)."""

    verts: np.ndarray
    counts: np.ndarray
    surface: np.ndarray
    corners: np.ndarray


def _kernel_arrays(
    verts: np.ndarray, counts: np.ndarray, circles: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The arrays as the kernels take them: float64 and int64, C-contiguous, circles (C, 3)."""
    return (
        np.ascontiguousarray(verts, dtype=np.float64).reshape(-1, verts.shape[1], 2),
        np.ascontiguousarray(counts, dtype=np.int64),
        np.ascontiguousarray(circles, dtype=np.float64).reshape(-1, 3),
    )


def covered_intervals(
    verts: np.ndarray,
    counts: np.ndarray,
    circles: np.ndarray,
    p: int,
    i: int,
    boxes: np.ndarray | None = None,
) -> list[tuple[float, float]]:
    """Disjoint, sorted parameters ``[t0, t1]`` (0 at vertex i, 1 at vertex i + 1) of edge i of
    polygon p along which another piece (polygon or disc) lies just beyond the edge.
    ``boxes`` (:func:`validity.cover_kernel.piece_boxes`) lets far pieces be skipped; computed
    when not given."""
    verts, counts, circles = _kernel_arrays(verts, counts, circles)
    if boxes is None:
        boxes = piece_boxes(verts, counts)
    cover = edge_cover(verts, counts, circles, np.ascontiguousarray(boxes), int(p), int(i))
    return [(float(lo), float(hi)) for lo, hi in cover]


def split_at_cover(verts: np.ndarray, counts: np.ndarray, circles: np.ndarray) -> SolidSurface:
    """The pieces ``verts (P, K, 2)``, ``counts (P,)`` (CCW, convex) and discs
    ``circles (C, 3)`` as a :class:`SolidSurface`: every edge split where cover by another
    piece begins or ends, each sub-edge marked surface or seam, and the contact corners."""
    out, out_counts, surface, inserted = split_kernel(*_kernel_arrays(verts, counts, circles))
    corners = corner_vertices(out, out_counts, surface)
    corners &= ~inserted
    return SolidSurface(out, out_counts, surface, corners)
