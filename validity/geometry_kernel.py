"""Signed distance between the part (a convex polygon) and static convex polygons and discs.

The one geometry kernel of every level: the geometric level asks for its sign (Eq. 9's
psi_n(q) >= 0), the contact levels for the nearby features. Arrays in, numbers out; compiled
with numba. Polygons are counter-clockwise, packed as ``verts (P, K, 2)`` with ``counts (P,)``
(padding repeats the last vertex: a zero-length edge, skipped); discs as ``circles (C, 3)``.

Signed distance: the Euclidean distance between the shapes when they are apart, minus the
penetration depth (the smallest translation that separates them) when they overlap. For convex
polygons the separating-axis test over edge normals gives the penetration depth exactly.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from validity.leaf_kernel import leaf_kernel

_EDGE_EPS = 1e-14


@leaf_kernel
def pose_vertices(body: np.ndarray, x: float, y: float, yaw: float, out: np.ndarray) -> None:
    """Write the world corners of a body polygon (body frame ``(n, 2)``) at pose into ``out``."""
    c, s = math.cos(yaw), math.sin(yaw)
    for i in range(body.shape[0]):
        bx, by = body[i, 0], body[i, 1]
        out[i, 0] = x + c * bx - s * by
        out[i, 1] = y + s * bx + c * by


@leaf_kernel
def point_segment_distance(
    px: float, py: float, ax: float, ay: float, bx: float, by: float
) -> float:
    """Distance from point p to segment ab."""
    ex, ey = bx - ax, by - ay
    ll = ex * ex + ey * ey
    t = 0.0
    if ll > _EDGE_EPS:
        t = ((px - ax) * ex + (py - ay) * ey) / ll
        t = min(1.0, max(0.0, t))
    dx, dy = px - (ax + t * ex), py - (ay + t * ey)
    return math.sqrt(dx * dx + dy * dy)


@leaf_kernel
def _edge_normal(a: np.ndarray, i: int, na: int) -> tuple[float, float, bool]:
    """Unit outward normal of edge i of CCW polygon a[:na]; False for a zero-length edge."""
    j = (i + 1) % na
    ex, ey = a[j, 0] - a[i, 0], a[j, 1] - a[i, 1]
    ll = math.sqrt(ex * ex + ey * ey)
    if ll <= _EDGE_EPS:
        return 0.0, 0.0, False
    return ey / ll, -ex / ll, True


@leaf_kernel
def _box_of(world: np.ndarray) -> tuple[float, float, float, float]:
    """(xmin, ymin, xmax, ymax) of points ``(n, 2)``."""
    x0, y0 = world[0, 0], world[0, 1]
    x1, y1 = x0, y0
    for i in range(1, world.shape[0]):
        x0, y0 = min(x0, world[i, 0]), min(y0, world[i, 1])
        x1, y1 = max(x1, world[i, 0]), max(y1, world[i, 1])
    return x0, y0, x1, y1


@leaf_kernel
def _max_separation(a: np.ndarray, na: int, b: np.ndarray, nb: int) -> float:
    """Largest separation of b from a's edge lines (outward normals of CCW a)."""
    best = -np.inf
    for i in range(na):
        nx, ny, ok = _edge_normal(a, i, na)
        if not ok:
            continue
        lowest = np.inf
        for k in range(nb):
            d = nx * (b[k, 0] - a[i, 0]) + ny * (b[k, 1] - a[i, 1])
            lowest = min(lowest, d)
        best = max(best, lowest)
    return best


@leaf_kernel
def _vertex_edge_distance(a: np.ndarray, na: int, b: np.ndarray, nb: int) -> float:
    """Smallest distance from a vertex of a to an edge of b."""
    best = np.inf
    for k in range(na):
        for i in range(nb):
            j = (i + 1) % nb
            d = point_segment_distance(a[k, 0], a[k, 1], b[i, 0], b[i, 1], b[j, 0], b[j, 1])
            best = min(best, d)
    return best


@leaf_kernel
def convex_signed_distance(a: np.ndarray, na: int, b: np.ndarray, nb: int) -> float:
    """Signed distance between convex CCW polygons a[:na] and b[:nb]."""
    sep = max(_max_separation(a, na, b, nb), _max_separation(b, nb, a, na))
    if sep <= 0.0:
        return sep
    return min(_vertex_edge_distance(a, na, b, nb), _vertex_edge_distance(b, nb, a, na))


@leaf_kernel
def circle_signed_distance(cx: float, cy: float, r: float, b: np.ndarray, nb: int) -> float:
    """Signed distance between the disc (c, r) and the convex CCW polygon b[:nb]."""
    inside = -np.inf
    for i in range(nb):
        nx, ny, ok = _edge_normal(b, i, nb)
        if ok:
            inside = max(inside, nx * (cx - b[i, 0]) + ny * (cy - b[i, 1]))
    if inside <= 0.0:
        return inside - r
    best = np.inf
    for i in range(nb):
        j = (i + 1) % nb
        best = min(best, point_segment_distance(cx, cy, b[i, 0], b[i, 1], b[j, 0], b[j, 1]))
    return best - r


@njit(cache=True)
def polygon_aabbs(verts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Axis-aligned boxes ``(P, 4)`` = (xmin, ymin, xmax, ymax) of packed polygons."""
    out = np.empty((verts.shape[0], 4))
    for p in range(verts.shape[0]):
        out[p, 0], out[p, 1] = np.inf, np.inf
        out[p, 2], out[p, 3] = -np.inf, -np.inf
        for k in range(counts[p]):
            out[p, 0] = min(out[p, 0], verts[p, k, 0])
            out[p, 1] = min(out[p, 1], verts[p, k, 1])
            out[p, 2] = max(out[p, 2], verts[p, k, 0])
            out[p, 3] = max(out[p, 3], verts[p, k, 1])
    return out


@leaf_kernel
def _box_gap(a0: float, a1: float, a2: float, a3: float, b: np.ndarray) -> float:
    """Distance between two axis-aligned boxes (0 when they overlap)."""
    dx = max(b[0] - a2, 0.0, a0 - b[2])
    dy = max(b[1] - a3, 0.0, a1 - b[3])
    return math.sqrt(dx * dx + dy * dy)


@leaf_kernel
def clearance_at(
    world: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    stop_below: float,
) -> float:
    """Smallest signed distance from the placed part ``world (n, 2)`` to every obstacle.

    Broad phase: an obstacle whose bounding box is farther than the best distance so far is
    skipped. Returns as soon as a distance below ``stop_below`` is found (use ``-inf`` for the
    exact minimum, ``0`` for a yes/no penetration test).
    """
    n = world.shape[0]
    x0, y0, x1, y1 = _box_of(world)
    best = np.inf
    for p in range(verts.shape[0]):
        gap = _box_gap(x0, y0, x1, y1, aabbs[p])
        if gap > 0.0 and gap >= best:  # overlapping boxes (gap 0) bound nothing below 0
            continue
        d = convex_signed_distance(world, n, verts[p], counts[p])
        if d < best:
            best = d
            if best < stop_below:
                return best
    for q in range(circles.shape[0]):
        cx, cy, r = circles[q, 0], circles[q, 1], circles[q, 2]
        gx = max(x0 - cx, 0.0, cx - x1)
        gy = max(y0 - cy, 0.0, cy - y1)
        gap = math.sqrt(gx * gx + gy * gy)
        if gap > 0.0 and gap - r >= best:
            continue
        d = circle_signed_distance(cx, cy, r, world, n)
        if d < best:
            best = d
            if best < stop_below:
                return best
    return best


@njit(cache=True)
def clearance_at_pose(
    body: np.ndarray,
    x: float,
    y: float,
    yaw: float,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    stop_below: float,
) -> float:
    """:func:`clearance_at` for the body polygon placed at ``(x, y, yaw)``."""
    world = np.empty_like(body)
    pose_vertices(body, x, y, yaw, world)
    return clearance_at(world, verts, counts, aabbs, circles, stop_below)


@leaf_kernel
def penetrates(
    world: np.ndarray, verts: np.ndarray, counts: np.ndarray, aabbs: np.ndarray, circles: np.ndarray
) -> bool:
    """True when the placed part overlaps an obstacle by more than touching (psi_n < 0).

    The sign of :func:`clearance_at` without its distances: boxes that do not overlap are
    skipped, and a separating axis ends the test for a polygon.
    """
    n = world.shape[0]
    x0, y0, x1, y1 = _box_of(world)
    for p in range(verts.shape[0]):
        b = aabbs[p]
        if b[0] > x1 or b[2] < x0 or b[1] > y1 or b[3] < y0:
            continue
        if _max_separation(world, n, verts[p], counts[p]) >= 0.0:
            continue
        if _max_separation(verts[p], counts[p], world, n) >= 0.0:
            continue
        return True
    for q in range(circles.shape[0]):
        cx, cy, r = circles[q, 0], circles[q, 1], circles[q, 2]
        if cx + r < x0 or cx - r > x1 or cy + r < y0 or cy - r > y1:
            continue
        if circle_signed_distance(cx, cy, r, world, n) < 0.0:
            return True
    return False


@leaf_kernel
def penetrates_deeper_than(
    world: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    polygon_slack: np.ndarray,
    disc_slack: np.ndarray,
) -> bool:
    """True when the placed part overlaps some obstacle by more than that obstacle's slack
    (length; ``polygon_slack (P,)``, ``disc_slack (C,)``): psi_n < -slack, the relaxed
    non-penetration of Eq. 9 (issue 21).

    A convex pair's penetration depth is the smallest overlap over its separating axes (the
    edge normals of both), so the depth is at most the slack exactly when some axis separates
    the pair to within it; a disc's depth is its radius minus its centre's signed distance.
    Zero slacks are :func:`penetrates`, bit for bit.
    """
    n = world.shape[0]
    x0, y0, x1, y1 = _box_of(world)
    for p in range(verts.shape[0]):
        b = aabbs[p]
        if b[0] > x1 or b[2] < x0 or b[1] > y1 or b[3] < y0:
            continue
        floor = -polygon_slack[p]
        if _max_separation(world, n, verts[p], counts[p]) >= floor:
            continue
        if _max_separation(verts[p], counts[p], world, n) >= floor:
            continue
        return True
    for q in range(circles.shape[0]):
        cx, cy, r = circles[q, 0], circles[q, 1], circles[q, 2]
        if cx + r < x0 or cx - r > x1 or cy + r < y0 or cy - r > y1:
            continue
        if circle_signed_distance(cx, cy, r, world, n) < -disc_slack[q]:
            return True
    return False


@leaf_kernel
def place_part(
    body: np.ndarray,
    bcounts: np.ndarray,
    bdiscs: np.ndarray,
    x: float,
    y: float,
    yaw: float,
    world: np.ndarray,
    wdiscs: np.ndarray,
) -> None:
    """Write a part's pieces (body frame: polygons ``body (Q, K, 2)`` with ``bcounts (Q,)``
    vertices, discs ``bdiscs (D, 3)``) placed at pose into ``world`` and ``wdiscs``."""
    c, s = math.cos(yaw), math.sin(yaw)
    for q in range(body.shape[0]):
        for i in range(body.shape[1]):
            bx, by = body[q, i, 0], body[q, i, 1]
            world[q, i, 0] = x + c * bx - s * by
            world[q, i, 1] = y + s * bx + c * by
    for k in range(bdiscs.shape[0]):
        bx, by = bdiscs[k, 0], bdiscs[k, 1]
        wdiscs[k, 0] = x + c * bx - s * by
        wdiscs[k, 1] = y + s * bx + c * by
        wdiscs[k, 2] = bdiscs[k, 2]


@leaf_kernel
def part_radius(body: np.ndarray, bcounts: np.ndarray, bdiscs: np.ndarray) -> float:
    """Largest distance from the centre of mass (the body frame's origin) to a point of the
    part: how far a turn of one radian moves any point of it."""
    radius = 0.0
    for q in range(body.shape[0]):
        for i in range(bcounts[q]):
            radius = max(radius, math.hypot(body[q, i, 0], body[q, i, 1]))
    for k in range(bdiscs.shape[0]):
        radius = max(radius, math.hypot(bdiscs[k, 0], bdiscs[k, 1]) + bdiscs[k, 2])
    return radius


@leaf_kernel
def _disc_clearance(cx, cy, r, verts, counts, aabbs, circles, best, stop_below) -> float:
    """``min(best, signed distance of the disc (c, r) to every obstacle)``, stopping below
    ``stop_below``."""
    for p in range(verts.shape[0]):
        b = aabbs[p]
        gx = max(b[0] - cx, 0.0, cx - b[2])
        gy = max(b[1] - cy, 0.0, cy - b[3])
        gap = math.sqrt(gx * gx + gy * gy)
        if gap > 0.0 and gap - r >= best:
            continue
        best = min(best, circle_signed_distance(cx, cy, r, verts[p], counts[p]))
        if best < stop_below:
            return best
    for q in range(circles.shape[0]):
        d = math.hypot(cx - circles[q, 0], cy - circles[q, 1]) - r - circles[q, 2]
        best = min(best, d)
        if best < stop_below:
            return best
    return best


@leaf_kernel
def part_clearance(
    world: np.ndarray,
    wcounts: np.ndarray,
    wdiscs: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    stop_below: float,
) -> float:
    """:func:`clearance_at` of a placed part of convex pieces ``world (Q, K, 2)`` (``wcounts``
    vertices each) and discs ``wdiscs (D, 3)``: the smallest over its pieces (a piece's
    penetration depth is its own, as an obstacle piece's is)."""
    if world.shape[0] == 1 and wdiscs.shape[0] == 0 and wcounts[0] == world.shape[1]:
        return clearance_at(world[0], verts, counts, aabbs, circles, stop_below)
    best = np.inf
    for q in range(world.shape[0]):
        best = min(
            best, clearance_at(world[q, : wcounts[q]], verts, counts, aabbs, circles, stop_below)
        )
        if best < stop_below:
            return best
    for k in range(wdiscs.shape[0]):
        best = _disc_clearance(
            wdiscs[k, 0],
            wdiscs[k, 1],
            wdiscs[k, 2],
            verts,
            counts,
            aabbs,
            circles,
            best,
            stop_below,
        )
        if best < stop_below:
            return best
    return best


@njit(cache=True)
def part_clearance_at_pose(
    body, bcounts, bdiscs, x, y, yaw, verts, counts, aabbs, circles, stop_below
) -> float:
    """:func:`part_clearance` for the part (body frame) placed at ``(x, y, yaw)``."""
    world = np.empty_like(body)
    wdiscs = np.empty_like(bdiscs)
    place_part(body, bcounts, bdiscs, x, y, yaw, world, wdiscs)
    return part_clearance(world, bcounts, wdiscs, verts, counts, aabbs, circles, stop_below)


@leaf_kernel
def part_penetrates_deeper_than(
    world: np.ndarray,
    wcounts: np.ndarray,
    wdiscs: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    polygon_slack: np.ndarray,
    disc_slack: np.ndarray,
) -> bool:
    """:func:`penetrates_deeper_than` for a placed part of convex pieces and discs: some
    piece overlaps some obstacle by more than that obstacle's slack."""
    if world.shape[0] == 1 and wdiscs.shape[0] == 0 and wcounts[0] == world.shape[1]:
        return penetrates_deeper_than(
            world[0], verts, counts, aabbs, circles, polygon_slack, disc_slack
        )
    for q in range(world.shape[0]):
        if penetrates_deeper_than(
            world[q, : wcounts[q]], verts, counts, aabbs, circles, polygon_slack, disc_slack
        ):
            return True
    for k in range(wdiscs.shape[0]):
        cx, cy, r = wdiscs[k, 0], wdiscs[k, 1], wdiscs[k, 2]
        for p in range(verts.shape[0]):
            b = aabbs[p]
            if b[0] > cx + r or b[2] < cx - r or b[1] > cy + r or b[3] < cy - r:
                continue
            if circle_signed_distance(cx, cy, r, verts[p], counts[p]) < -polygon_slack[p]:
                return True
        for q in range(circles.shape[0]):
            d = math.hypot(cx - circles[q, 0], cy - circles[q, 1]) - r - circles[q, 2]
            if d < -disc_slack[q]:
                return True
    return False


@leaf_kernel
def part_penetrates(world, wcounts, wdiscs, verts, counts, aabbs, circles) -> bool:
    """:func:`penetrates` for a placed part of convex pieces and discs (psi_n < 0 anywhere)."""
    if world.shape[0] == 1 and wdiscs.shape[0] == 0 and wcounts[0] == world.shape[1]:
        return penetrates(world[0], verts, counts, aabbs, circles)
    for q in range(world.shape[0]):
        if penetrates(world[q, : wcounts[q]], verts, counts, aabbs, circles):
            return True
    for k in range(wdiscs.shape[0]):
        cx, cy, r = wdiscs[k, 0], wdiscs[k, 1], wdiscs[k, 2]
        if _disc_clearance(cx, cy, r, verts, counts, aabbs, circles, np.inf, 0.0) < 0.0:
            return True
    return False
