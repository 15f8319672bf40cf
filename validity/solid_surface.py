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
face: it is no contact corner.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from validity.contact_kernel import corner_vertices

_PARALLEL = 1e-12  # |cos| between an edge and a piece's edge normal below this: parallel
_T_TOL = 1e-9  # parameter distance (fraction of an edge) below which two cover ends are one


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


def _polygon_cover(
    a: np.ndarray, d: np.ndarray, n: np.ndarray, poly: np.ndarray, tol: float
) -> tuple[float, float] | None:
    """Parameters ``[t0, t1]`` of the edge ``a + t d`` whose outside (just beyond, along the
    outward normal n) lies inside the convex CCW polygon ``poly``; None when no stretch does."""
    lo, hi = -np.inf, np.inf
    length = float(np.hypot(*d))
    m = len(poly)
    for k in range(m):
        e = poly[(k + 1) % m] - poly[k]
        el = float(np.hypot(*e))
        if el <= 1e-14:
            continue
        normal = np.array([e[1], -e[0]]) / el  # outward normal of the piece's edge k
        alpha = float(normal @ (a - poly[k]))  # normal . (s(t) - q_k) = alpha + beta t
        beta = float(normal @ d)
        if abs(beta) <= _PARALLEL * length:
            if alpha > tol:
                return None  # the whole edge line is outside this side of the piece
            if alpha >= -tol and float(normal @ n) >= 0.0:
                return None  # collinear, the piece on the edge's inner side: no cover
            continue  # inside this side, or collinear with the piece beyond the edge
        t = -alpha / beta
        if beta > 0.0:
            hi = min(hi, t)
        else:
            lo = max(lo, t)
    lo, hi = max(lo, 0.0), min(hi, 1.0)
    return (lo, hi) if hi - lo > _T_TOL else None


def _disc_cover(
    a: np.ndarray, d: np.ndarray, disc: np.ndarray, tol: float
) -> tuple[float, float] | None:
    """Parameters ``[t0, t1]`` of the edge ``a + t d`` strictly inside the disc (cx, cy, r);
    None when the edge line passes within ``tol`` of tangency (or outside)."""
    dd = float(d @ d)
    if dd <= 0.0:
        return None
    w = disc[:2] - a
    foot = float(w @ d) / dd  # parameter of the point nearest the centre
    miss = abs(float(w[0] * d[1] - w[1] * d[0])) / np.sqrt(dd)  # centre to the line
    if disc[2] - miss <= tol:
        return None
    half = np.sqrt((disc[2] - miss) * (disc[2] + miss) / dd)
    lo, hi = max(foot - half, 0.0), min(foot + half, 1.0)
    return (lo, hi) if hi - lo > _T_TOL else None


def _merge(intervals: list[tuple[float, float]]) -> list[tuple[float, float]]:
    out: list[tuple[float, float]] = []
    for lo, hi in sorted(intervals):
        if out and lo <= out[-1][1] + _T_TOL:
            out[-1] = (out[-1][0], max(out[-1][1], hi))
        else:
            out.append((lo, hi))
    return out


def piece_boxes(verts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """``(P, 4)``: (xmin, ymin, xmax, ymax) of each piece."""
    boxes = np.empty((verts.shape[0], 4))
    for p in range(verts.shape[0]):
        v = verts[p, : int(counts[p])]
        boxes[p, :2], boxes[p, 2:] = v.min(axis=0), v.max(axis=0)
    return boxes


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
    ``boxes`` (:func:`piece_boxes`) lets far pieces be skipped; computed when not given."""
    n = int(counts[p])
    a, b = verts[p, i], verts[p, (i + 1) % n]
    d = b - a
    length = float(np.hypot(*d))
    if length <= 1e-14:
        return []
    normal = np.array([d[1], -d[0]]) / length
    scale = 1.0 + float(np.max(np.abs(verts[p, :n])))
    tol = 1e-12 * scale
    if boxes is None:
        boxes = piece_boxes(verts, counts)
    x0, x1 = min(a[0], b[0]) - tol, max(a[0], b[0]) + tol
    y0, y1 = min(a[1], b[1]) - tol, max(a[1], b[1]) + tol
    found = []
    for q in range(verts.shape[0]):
        box = boxes[q]
        if box[0] > x1 or box[2] < x0 or box[1] > y1 or box[3] < y0:
            continue  # a piece apart from the edge covers none of it
        if q != p:
            cover = _polygon_cover(a, d, normal, verts[q, : int(counts[q])], tol)
            if cover is not None:
                found.append(cover)
    for disc in circles:
        cover = _disc_cover(a, d, disc, tol)
        if cover is not None:
            found.append(cover)
    return _merge(found)


def split_at_cover(verts: np.ndarray, counts: np.ndarray, circles: np.ndarray) -> SolidSurface:
    """The pieces ``verts (P, K, 2)``, ``counts (P,)`` (CCW, convex) and discs
    ``circles (C, 3)`` as a :class:`SolidSurface`: every edge split where cover by another
    piece begins or ends, each sub-edge marked surface or seam, and the contact corners."""
    pieces: list[list[np.ndarray]] = []
    flags: list[list[bool]] = []
    inserted: list[list[bool]] = []
    boxes = piece_boxes(verts, counts)
    for p in range(verts.shape[0]):
        n = int(counts[p])
        pts, surf, new = [], [], []
        for i in range(n):
            a, b = verts[p, i], verts[p, (i + 1) % n]
            cover = covered_intervals(verts, counts, circles, p, i, boxes)
            cuts = sorted({t for lo, hi in cover for t in (lo, hi) if _T_TOL < t < 1.0 - _T_TOL})
            bounds = [0.0, *cuts, 1.0]
            for k in range(len(bounds) - 1):
                mid = 0.5 * (bounds[k] + bounds[k + 1])
                pts.append(a + bounds[k] * (b - a))
                new.append(k > 0)
                surf.append(not any(lo <= mid <= hi for lo, hi in cover))
        pieces.append(pts)
        flags.append(surf)
        inserted.append(new)
    k_max = max((len(p) for p in pieces), default=3)
    out = np.zeros((len(pieces), k_max, 2))
    out_counts = np.zeros(len(pieces), dtype=np.int64)
    surface = np.ones((len(pieces), k_max), dtype=np.bool_)
    for p, pts in enumerate(pieces):
        out[p, : len(pts)] = pts
        out[p, len(pts) :] = pts[-1]
        out_counts[p] = len(pts)
        surface[p, : len(pts)] = flags[p]
    corners = corner_vertices(out, out_counts, surface)
    for p, new in enumerate(inserted):
        corners[p, : len(new)] &= ~np.asarray(new, dtype=np.bool_)
    return SolidSurface(out, out_counts, surface, corners)
