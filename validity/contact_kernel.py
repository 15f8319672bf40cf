"""Candidate contacts between the part and the static obstacles, for the contact levels.

A contact is a point of the part with a signed gap psi_n to an obstacle (negative: penetration
depth), the unit normal n along which the obstacle pushes the part, and the tangent
t = (-n_y, n_x). Contacts are reported for every feature pair closer than a margin, so the
time stepper of Eq. 7 sees contacts "in or about to be in contact" and its psi_n / h term lets
each one close at most its gap in a step.

The part and the polygons are convex, so two of them first touch vertex-to-edge (or
vertex-to-vertex): the candidates are each part corner against each nearby polygon, each
polygon corner against the part (skipped when its nearest point on the part is a part corner,
which the first pass already reports), and each disc centre against the part. Signed distances
use the same separating-axis rule as :mod:`validity.geometry_kernel`, so both levels agree on
what penetrates. Arrays in, numbers out; compiled with numba.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from validity.geometry_kernel import _box_gap, _box_of, _edge_normal

MAX_CONTACTS = 12  # a planar convex part touches at most a few features; deeper ones are kept
_TINY = 1e-14


@njit(cache=True)
def point_polygon_feature(
    px: float, py: float, b: np.ndarray, nb: int, cutoff: float = np.inf
) -> tuple[float, float, float, float, float, bool]:
    """Signed distance from point p to the convex CCW polygon b[:nb], with its nearest feature.

    Returns ``(gap, nx, ny, cx, cy, at_vertex)``: the signed distance (negative inside: the
    depth to the nearest edge line), the unit outward normal of b that pushes p out, the
    nearest point c of b's boundary, and whether c is a vertex of b. When p is at least
    ``cutoff`` outside an edge line, that separation (a lower bound of the distance) is
    returned as the gap at once, with the edge's normal and foot point.
    """
    inside, in_nx, in_ny, in_i = -np.inf, 0.0, 0.0, -1
    for i in range(nb):
        nx, ny, ok = _edge_normal(b, i, nb)
        if ok:
            d = nx * (px - b[i, 0]) + ny * (py - b[i, 1])
            if d > inside:
                inside, in_nx, in_ny, in_i = d, nx, ny, i
    if (inside <= 0.0 or inside >= cutoff) and in_i >= 0:
        return inside, in_nx, in_ny, px - inside * in_nx, py - inside * in_ny, False
    best, cx, cy, vertex = np.inf, px, py, False
    for i in range(nb):
        j = (i + 1) % nb
        ax, ay = b[i, 0], b[i, 1]
        ex, ey = b[j, 0] - ax, b[j, 1] - ay
        ll = ex * ex + ey * ey
        t = 0.0
        if ll > _TINY:
            t = min(1.0, max(0.0, ((px - ax) * ex + (py - ay) * ey) / ll))
        qx, qy = ax + t * ex, ay + t * ey
        d = math.hypot(px - qx, py - qy)
        if d < best:
            best, cx, cy, vertex = d, qx, qy, (t <= 0.0 or t >= 1.0)
    if best > _TINY:
        return best, (px - cx) / best, (py - cy) / best, cx, cy, vertex
    return best, in_nx, in_ny, cx, cy, vertex  # on the boundary: the edge's own normal


@njit(cache=True)
def _add(contacts: np.ndarray, nc: int, gap, nx, ny, px, py) -> int:
    """Append a row (gap, nx, ny, px, py); when full, it replaces the row with the largest gap."""
    k = nc
    if nc == contacts.shape[0]:
        k = 0
        for i in range(1, nc):
            if contacts[i, 0] > contacts[k, 0]:
                k = i
        if contacts[k, 0] <= gap:
            return nc
    contacts[k, 0], contacts[k, 1], contacts[k, 2] = gap, nx, ny
    contacts[k, 3], contacts[k, 4] = px, py
    return max(nc, k + 1)


@njit(cache=True)
def find_contacts(
    world: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    margin: float,
    contacts: np.ndarray,
) -> tuple[int, float]:
    """Contacts of the placed part ``world (n, 2)`` with gap below ``margin``.

    Writes rows ``(gap, nx, ny, px, py)`` into ``contacts (MAX_CONTACTS, 5)``: the point p is
    on the part and n points from the obstacle into the part. Returns ``(count, clear)``:
    ``clear`` is a lower bound on the distance to every obstacle that gave no contact (inf when
    there is none), so a caller with no contacts knows how far the part may move before one
    can appear. Broad phase: obstacles whose bounding box is ``margin`` or more away are
    bounded by that box gap and not tested further.
    """
    n = world.shape[0]
    x0, y0, x1, y1 = _box_of(world)
    nc = 0
    clear = np.inf
    for p in range(verts.shape[0]):
        gap = _box_gap(x0, y0, x1, y1, aabbs[p])
        if gap >= margin:
            clear = min(clear, gap)
            continue
        b, nb = verts[p], counts[p]
        nearest = np.inf
        for k in range(n):
            d, nx, ny, _, _, _ = point_polygon_feature(world[k, 0], world[k, 1], b, nb, margin)
            nearest = min(nearest, d)
            if d < margin:
                nc = _add(contacts, nc, d, nx, ny, world[k, 0], world[k, 1])
        for j in range(nb):
            d, nx, ny, cx, cy, at_vertex = point_polygon_feature(b[j, 0], b[j, 1], world, n, margin)
            nearest = min(nearest, d)
            if d < margin and not (d > 0.0 and at_vertex):
                nc = _add(contacts, nc, d, -nx, -ny, cx, cy)
        if nearest >= margin:
            clear = min(clear, nearest)
    for q in range(circles.shape[0]):
        ox, oy, r = circles[q, 0], circles[q, 1], circles[q, 2]
        gx = max(x0 - ox, 0.0, ox - x1)
        gy = max(y0 - oy, 0.0, oy - y1)
        gap = math.hypot(gx, gy) - r
        if gap >= margin:
            clear = min(clear, gap)
            continue
        d, nx, ny, cx, cy, _ = point_polygon_feature(ox, oy, world, n, margin + r)
        d -= r
        if d < margin:
            nc = _add(contacts, nc, d, -nx, -ny, cx, cy)
        else:
            clear = min(clear, d)
    return nc, clear
