"""Compiled cover split of a scene's obstacle pieces (:mod:`validity.solid_surface`).

A made feeder differs from the nominal one in every vertex, so its surface is decided once per
trial (issue 21: in Python this was 18% of a verdict trial). These kernels compute, per edge of
each convex piece, the parameter intervals along which another piece (polygon or disc) lies
just beyond the edge, and split every edge at the interval ends. The arithmetic is that of the
reference construction term for term (no reassociation, no fused multiply-add), so the split
vertices and flags are the same floats.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

PARALLEL = 1e-12  # |cos| between an edge and a piece's edge normal below this: parallel
T_TOL = 1e-9  # parameter distance (fraction of an edge) below which two cover ends are one
EDGE_MIN = 1e-14  # an edge shorter than this (length) is a padding repeat: it covers nothing


@njit(cache=True)
def piece_boxes(verts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """``(P, 4)``: (xmin, ymin, xmax, ymax) of each piece."""
    boxes = np.empty((verts.shape[0], 4))
    for p in range(verts.shape[0]):
        x0, y0 = verts[p, 0, 0], verts[p, 0, 1]
        x1, y1 = x0, y0
        for k in range(1, counts[p]):
            x0, x1 = min(x0, verts[p, k, 0]), max(x1, verts[p, k, 0])
            y0, y1 = min(y0, verts[p, k, 1]), max(y1, verts[p, k, 1])
        boxes[p, 0], boxes[p, 1], boxes[p, 2], boxes[p, 3] = x0, y0, x1, y1
    return boxes


@njit(cache=True)
def _polygon_cover(ax, ay, dx, dy, nx, ny, poly, m, tol):
    """``(ok, t0, t1)``: the parameters of the edge ``a + t d`` whose outside (beyond it along
    its outward normal n) lies inside the convex CCW polygon ``poly[:m]``; ok False when no
    stretch of it does."""
    lo, hi = -np.inf, np.inf
    length = math.hypot(dx, dy)
    for k in range(m):
        j = (k + 1) % m
        ex, ey = poly[j, 0] - poly[k, 0], poly[j, 1] - poly[k, 1]
        el = math.hypot(ex, ey)
        if el <= EDGE_MIN:
            continue
        px, py = ey / el, -ex / el  # outward normal of the piece's edge k
        alpha = px * (ax - poly[k, 0]) + py * (ay - poly[k, 1])  # p . (s(t) - q_k) = alpha + beta t
        beta = px * dx + py * dy
        if abs(beta) <= PARALLEL * length:
            if alpha > tol:
                return False, 0.0, 0.0  # the whole edge line is outside this side of the piece
            if alpha >= -tol and px * nx + py * ny >= 0.0:
                return False, 0.0, 0.0  # collinear, the piece on the edge's inner side
            continue  # inside this side, or collinear with the piece beyond the edge
        t = -alpha / beta
        if beta > 0.0:
            hi = min(hi, t)
        else:
            lo = max(lo, t)
    lo, hi = max(lo, 0.0), min(hi, 1.0)
    return hi - lo > T_TOL, lo, hi


@njit(cache=True)
def _disc_cover(ax, ay, dx, dy, cx, cy, r, tol):
    """``(ok, t0, t1)``: the parameters of the edge ``a + t d`` strictly inside the disc
    (cx, cy, r); ok False when the edge line passes within ``tol`` of tangency (or outside)."""
    dd = dx * dx + dy * dy
    if dd <= 0.0:
        return False, 0.0, 0.0
    wx, wy = cx - ax, cy - ay
    foot = (wx * dx + wy * dy) / dd  # parameter of the point nearest the centre
    miss = abs(wx * dy - wy * dx) / np.sqrt(dd)  # centre to the line
    if r - miss <= tol:
        return False, 0.0, 0.0
    half = np.sqrt((r - miss) * (r + miss) / dd)
    lo, hi = max(foot - half, 0.0), min(foot + half, 1.0)
    return hi - lo > T_TOL, lo, hi


@njit(cache=True)
def edge_cover(
    verts: np.ndarray,
    counts: np.ndarray,
    circles: np.ndarray,
    boxes: np.ndarray,
    p: int,
    i: int,
) -> np.ndarray:
    """``(m, 2)``: the disjoint, sorted parameters ``[t0, t1]`` (0 at vertex i, 1 at vertex
    i + 1) of edge i of polygon p along which another piece lies just beyond the edge."""
    n = counts[p]
    j = (i + 1) % n
    ax, ay = verts[p, i, 0], verts[p, i, 1]
    bx, by = verts[p, j, 0], verts[p, j, 1]
    dx, dy = bx - ax, by - ay
    length = math.hypot(dx, dy)
    found = np.empty((verts.shape[0] + circles.shape[0], 2))
    if length <= EDGE_MIN:
        return found[:0]
    nx, ny = dy / length, -dx / length
    big = 0.0
    for k in range(n):
        big = max(big, abs(verts[p, k, 0]), abs(verts[p, k, 1]))
    tol = 1e-12 * (1.0 + big)
    x0, x1 = min(ax, bx) - tol, max(ax, bx) + tol
    y0, y1 = min(ay, by) - tol, max(ay, by) + tol
    m = 0
    for q in range(verts.shape[0]):
        if boxes[q, 0] > x1 or boxes[q, 2] < x0 or boxes[q, 1] > y1 or boxes[q, 3] < y0:
            continue  # a piece apart from the edge covers none of it
        if q != p:
            ok, lo, hi = _polygon_cover(ax, ay, dx, dy, nx, ny, verts[q], counts[q], tol)
            if ok:
                found[m, 0], found[m, 1] = lo, hi
                m += 1
    for c in range(circles.shape[0]):
        ok, lo, hi = _disc_cover(ax, ay, dx, dy, circles[c, 0], circles[c, 1], circles[c, 2], tol)
        if ok:
            found[m, 0], found[m, 1] = lo, hi
            m += 1
    return _merge(found[:m])


@njit(cache=True)
def _merge(intervals: np.ndarray) -> np.ndarray:
    """The union of ``intervals (m, 2)`` as disjoint sorted intervals, ends within
    :data:`T_TOL` joined (sorted by start, then end)."""
    m = intervals.shape[0]
    order = np.arange(m)
    for a in range(1, m):  # insertion sort: a handful of intervals per edge
        k = order[a]
        b = a - 1
        while b >= 0 and (
            intervals[order[b], 0] > intervals[k, 0]
            or (
                intervals[order[b], 0] == intervals[k, 0]
                and intervals[order[b], 1] > intervals[k, 1]
            )
        ):
            order[b + 1] = order[b]
            b -= 1
        order[b + 1] = k
    out = np.empty((m, 2))
    r = 0
    for a in range(m):
        lo, hi = intervals[order[a], 0], intervals[order[a], 1]
        if r > 0 and lo <= out[r - 1, 1] + T_TOL:
            out[r - 1, 1] = max(out[r - 1, 1], hi)
        else:
            out[r, 0], out[r, 1] = lo, hi
            r += 1
    return out[:r]


@njit(cache=True)
def _cuts(cover: np.ndarray) -> np.ndarray:
    """The distinct interval ends strictly inside ``(T_TOL, 1 - T_TOL)``, sorted."""
    ends = np.empty(2 * cover.shape[0])
    m = 0
    for r in range(cover.shape[0]):
        for t in (cover[r, 0], cover[r, 1]):
            if T_TOL < t < 1.0 - T_TOL:
                ends[m] = t
                m += 1
    ends = np.sort(ends[:m])
    out = np.empty(m)
    k = 0
    for a in range(m):
        if k == 0 or ends[a] != out[k - 1]:
            out[k] = ends[a]
            k += 1
    return out[:k]


@njit(cache=True)
def split_kernel(
    verts: np.ndarray, counts: np.ndarray, circles: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(verts (P, K', 2), counts (P,), surface (P, K'), inserted (P, K'))``: every edge of
    the pieces split where cover by another piece begins or ends; ``surface`` True for
    sub-edges with no cover along them (padding True), ``inserted`` True for vertices the split
    added (padding False). ``K'`` is 3 when there are no pieces."""
    P = verts.shape[0]
    boxes = piece_boxes(verts, counts)
    total = 0
    for p in range(P):
        total += counts[p]
    # per original edge: its cover intervals and cuts, kept in flat buffers
    starts = np.zeros(total + 1, dtype=np.int64)
    cut_starts = np.zeros(total + 1, dtype=np.int64)
    covers = np.empty((0, 2))
    cuts = np.empty(0)
    cover_list = []
    cut_list = []
    e = 0
    for p in range(P):
        for i in range(counts[p]):
            cover = edge_cover(verts, counts, circles, boxes, p, i)
            cover_list.append(cover)
            c = _cuts(cover)
            cut_list.append(c)
            starts[e + 1] = starts[e] + cover.shape[0]
            cut_starts[e + 1] = cut_starts[e] + c.shape[0]
            e += 1
    covers = np.empty((starts[total], 2))
    cuts = np.empty(cut_starts[total])
    for e in range(total):
        covers[starts[e] : starts[e + 1]] = cover_list[e]
        cuts[cut_starts[e] : cut_starts[e + 1]] = cut_list[e]
    new_counts = np.zeros(P, dtype=np.int64)
    e = 0
    for p in range(P):
        for _ in range(counts[p]):
            new_counts[p] += 1 + cut_starts[e + 1] - cut_starts[e]
            e += 1
    k_max = 3
    if P > 0:
        k_max = new_counts.max()
    out = np.zeros((P, k_max, 2))
    surface = np.ones((P, k_max), dtype=np.bool_)
    inserted = np.zeros((P, k_max), dtype=np.bool_)
    e = 0
    for p in range(P):
        n = counts[p]
        w = 0
        for i in range(n):
            j = (i + 1) % n
            ax, ay = verts[p, i, 0], verts[p, i, 1]
            dx, dy = verts[p, j, 0] - ax, verts[p, j, 1] - ay
            c0, c1 = cut_starts[e], cut_starts[e + 1]
            for k in range(c1 - c0 + 1):
                t0 = 0.0 if k == 0 else cuts[c0 + k - 1]
                t1 = 1.0 if k == c1 - c0 else cuts[c0 + k]
                mid = 0.5 * (t0 + t1)
                out[p, w, 0], out[p, w, 1] = ax + t0 * dx, ay + t0 * dy
                inserted[p, w] = k > 0
                covered = False
                for r in range(starts[e], starts[e + 1]):
                    if covers[r, 0] <= mid <= covers[r, 1]:
                        covered = True
                surface[p, w] = not covered
                w += 1
            e += 1
        for k in range(w, k_max):
            out[p, k, 0], out[p, k, 1] = out[p, w - 1, 0], out[p, w - 1, 1]
    return out, new_counts, surface, inserted
