"""Compiled kernels of a feeder's build (issue 21, "the cost of a trial"): the mitred walls,
the crossing test between interior edges, and a conservative clearance test of the part.

Every verdict trial builds its feeder as made (12 parameters perturbed), so the build is paid
per drop. These kernels give the walls bit for bit as the numpy code they replace did, and
decide the two shapely tests only where floating point decides them for certain; anything
else is handed back to shapely (:mod:`feeders.feeder`), which stays the reference.

Floating point, spelled out so that the walls are bit-identical: the side of a vertex in the
mitre clip was ``(poly - point) @ normal``, which OpenBLAS (dgemv, the Haswell kernel) gives as
``fma(dx, nx, dy * ny)`` for two rows or more and numpy as ``dx * nx + dy * ny`` for one row;
the quad's length is CPython's ``math.hypot`` (passed in), the edge normal's length libm's
``hypot`` (numba's and numpy's ``np.hypot``). No other operation is fused or reordered.
"""

from __future__ import annotations

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

WALL_CAPACITY = 16  # vertices: a quad clipped twice has at most 2 * 2 * 4 (Sutherland-Hodgman)
UNSURE = 2  # a pair or a clearance that only shapely may decide
CROSSING = 1  # a pair of edges that certainly meet other than at a shared end
# Shewchuk's bound on the rounding error of a 2 x 2 orientation determinant (relative to the
# sum of its two products' magnitudes), eps = 2^-53.
_EPS = 2.0**-53
_ORIENT_ERROR = (3.0 + 16.0 * _EPS) * _EPS


@intrinsic
def _fma(typingctx, a, b, c):  # type: ignore[no-untyped-def]
    """a * b + c rounded once (LLVM's ``llvm.fma.f64``)."""
    sig = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
        double = ir.DoubleType()
        fnty = ir.FunctionType(double, [double, double, double])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.fma.f64")
        return builder.call(fn, args)

    return sig, codegen


@numba.njit(cache=True)
def _clip(
    poly: np.ndarray, count: int, px: float, py: float, nx: float, ny: float
) -> tuple[np.ndarray, int]:
    """Sutherland-Hodgman: the part of the convex ``poly[:count]`` where
    ``(x - p) . n >= 0``, vertices closer than 1e-12 to the one before them dropped."""
    side = np.empty(count)
    for i in range(count):
        dx = poly[i, 0] - px
        dy = poly[i, 1] - py
        if count == 1:
            side[i] = dx * nx + dy * ny
        else:
            side[i] = _fma(dx, nx, dy * ny)  # type: ignore[call-arg]
    out = np.empty((WALL_CAPACITY, 2))
    m = 0
    for i in range(count):
        j = (i + 1) % count
        if side[i] >= 0:
            out[m, 0] = poly[i, 0]
            out[m, 1] = poly[i, 1]
            m += 1
        if (side[i] >= 0) != (side[j] >= 0):
            t = side[i] / (side[i] - side[j])
            out[m, 0] = poly[i, 0] + t * (poly[j, 0] - poly[i, 0])
            out[m, 1] = poly[i, 1] + t * (poly[j, 1] - poly[i, 1])
            m += 1
    kept = np.empty((WALL_CAPACITY, 2))
    k = 0
    for i in range(m):
        before = (i - 1) % m
        if np.hypot(out[i, 0] - out[before, 0], out[i, 1] - out[before, 1]) > 1e-12:
            kept[k, 0] = out[i, 0]
            kept[k, 1] = out[i, 1]
            k += 1
    return kept, k


@numba.njit(cache=True)
def mitred_walls(
    segments: np.ndarray, lengths: np.ndarray, thickness: float
) -> tuple[np.ndarray, np.ndarray]:
    """The walls of :func:`feeders.feeder.walls` from the edges ``segments`` ``(n, 2, 2)``
    (start, end) and their lengths (``math.hypot``): ``(n, WALL_CAPACITY, 2)`` vertices and
    ``(n,)`` counts. A count of -1 says a clip left no vertex, which the numpy code could not
    clip further (the caller decides)."""
    n = segments.shape[0]
    verts = np.zeros((n, WALL_CAPACITY, 2))
    counts = np.full(n, 4, dtype=np.int64)
    normals = np.empty((n, 2))
    for i in range(n):
        x0, y0 = segments[i, 0, 0], segments[i, 0, 1]
        x1, y1 = segments[i, 1, 0], segments[i, 1, 1]
        dx, dy = x1 - x0, y1 - y0
        qx = dy / lengths[i] * thickness
        qy = -dx / lengths[i] * thickness
        verts[i, 0, 0], verts[i, 0, 1] = x0, y0
        verts[i, 1, 0], verts[i, 1, 1] = x0 + qx, y0 + qy
        verts[i, 2, 0], verts[i, 2, 1] = x1 + qx, y1 + qy
        verts[i, 3, 0], verts[i, 3, 1] = x1, y1
        norm = np.hypot(dx, dy)
        normals[i, 0] = dy / norm
        normals[i, 1] = -dx / norm
    for cur in range(n):
        prev = (cur - 1) % n
        dpx = segments[prev, 1, 0] - segments[prev, 0, 0]
        dpy = segments[prev, 1, 1] - segments[prev, 0, 1]
        dcx = segments[cur, 1, 0] - segments[cur, 0, 0]
        dcy = segments[cur, 1, 1] - segments[cur, 0, 1]
        if dpx * dcy - dpy * dcx >= 0:
            continue  # left turn: the walls part on the outside, nothing to clip
        bx = normals[prev, 0] + normals[cur, 0]
        by = normals[prev, 1] + normals[cur, 1]
        ax, ay = -by, bx
        if ax * dcx + ay * dcy < 0:
            ax, ay = -ax, -ay
        vx, vy = segments[cur, 0, 0], segments[cur, 0, 1]
        for wall, sx, sy in ((cur, ax, ay), (prev, -ax, -ay)):
            if counts[wall] < 1:
                counts[wall] = -1
                continue
            clipped, k = _clip(verts[wall], counts[wall], vx, vy, sx, sy)
            verts[wall, :] = 0.0
            verts[wall, :k] = clipped[:k]
            counts[wall] = k
    for i in range(n):
        if counts[i] < 1:
            counts[i] = -1
    return verts, counts


@numba.njit(cache=True)
def _orientation(
    ax: float, ay: float, bx: float, by: float, cx: float, cy: float
) -> tuple[int, bool]:
    """Sign of the turn a -> b -> c (+1 left, -1 right, 0 straight) and whether it is
    certain (Shewchuk's filter; a sign below the error bound is uncertain)."""
    left = (ax - cx) * (by - cy)
    right = (ay - cy) * (bx - cx)
    det = left - right
    if left > 0.0:
        if right <= 0.0:
            return 1, True  # exact signs of the products (differences round to 0 only at 0)
        total = left + right
    elif left < 0.0:
        if right >= 0.0:
            return -1, True
        total = -left - right
    else:
        # left is 0: one of its factors is exactly 0 unless the product underflowed
        exact = (ax - cx) == 0.0 or (by - cy) == 0.0
        exact = exact and (right != 0.0 or (ay - cy) == 0.0 or (bx - cx) == 0.0)
        return (1 if det > 0.0 else (-1 if det < 0.0 else 0)), exact
    bound = _ORIENT_ERROR * total
    if det > bound:
        return 1, True
    if -det > bound:
        return -1, True
    return 0, False


@numba.njit(cache=True)
def _pair(segments: np.ndarray, i: int, j: int, n: int) -> int:
    """0 if edges ``i < j`` certainly meet nowhere but at a shared end (adjacent edges),
    :data:`CROSSING` if they certainly meet elsewhere, else :data:`UNSURE`."""
    ax, ay = segments[i, 0, 0], segments[i, 0, 1]
    bx, by = segments[i, 1, 0], segments[i, 1, 1]
    cx, cy = segments[j, 0, 0], segments[j, 0, 1]
    dx, dy = segments[j, 1, 0], segments[j, 1, 1]
    if (ax == bx and ay == by) or (cx == dx and cy == dy):
        return UNSURE
    after = j == i + 1
    before = i == 0 and j == n - 1
    if after or before:
        if after and before:
            return UNSURE
        if after and bx == cx and by == cy:
            turn, sure = _orientation(ax, ay, bx, by, dx, dy)
        elif before and ax == dx and ay == dy:
            turn, sure = _orientation(cx, cy, dx, dy, bx, by)
        else:
            return UNSURE
        # a shared end and a certain turn: they meet at that end only
        return 0 if sure and turn != 0 else UNSURE
    o1, s1 = _orientation(ax, ay, bx, by, cx, cy)
    o2, s2 = _orientation(ax, ay, bx, by, dx, dy)
    o3, s3 = _orientation(cx, cy, dx, dy, ax, ay)
    o4, s4 = _orientation(cx, cy, dx, dy, bx, by)
    if not (s1 and s2 and s3 and s4) or o1 == 0 or o2 == 0 or o3 == 0 or o4 == 0:
        return UNSURE  # touching or nearly: shapely decides
    return CROSSING if o1 != o2 and o3 != o4 else 0


@numba.njit(cache=True)
def first_suspect_pair(segments: np.ndarray, after: int) -> tuple[int, int, int, int]:
    """The first pair ``(k, i, j, status)`` (k its number) of edges ``(n, 2, 2)``, in the order of
    ``np.triu_indices(n, 1)`` and after the pair numbered ``after`` (-1: from the first), whose
    bounding boxes meet and that is not certainly apart: status :data:`CROSSING` or
    :data:`UNSURE`; ``(-1, -1, -1, 0)`` if there is none."""
    n = segments.shape[0]
    k = -1
    for i in range(n):
        lx = min(segments[i, 0, 0], segments[i, 1, 0])
        hx = max(segments[i, 0, 0], segments[i, 1, 0])
        ly = min(segments[i, 0, 1], segments[i, 1, 1])
        hy = max(segments[i, 0, 1], segments[i, 1, 1])
        for j in range(i + 1, n):
            k += 1
            if k <= after:
                continue
            mx = min(segments[j, 0, 0], segments[j, 1, 0])
            Mx = max(segments[j, 0, 0], segments[j, 1, 0])
            my = min(segments[j, 0, 1], segments[j, 1, 1])
            My = max(segments[j, 0, 1], segments[j, 1, 1])
            if not (lx <= Mx and ly <= My and mx <= hx and my <= hy):
                continue
            status = _pair(segments, i, j, n)
            if status != 0:
                return k, i, j, status
    return -1, -1, -1, 0


@numba.njit(cache=True)
def _separation(a: np.ndarray, na: int, b: np.ndarray, nb: int, ux: float, uy: float) -> float:
    """Gap between the projections of ``a[:na]`` and ``b[:nb]`` on the axis u (negative
    where they overlap)."""
    amin = np.inf
    amax = -np.inf
    for i in range(na):
        s = a[i, 0] * ux + a[i, 1] * uy
        amin = min(amin, s)
        amax = max(amax, s)
    bmin = np.inf
    bmax = -np.inf
    for i in range(nb):
        s = b[i, 0] * ux + b[i, 1] * uy
        bmin = min(bmin, s)
        bmax = max(bmax, s)
    return max(bmin - amax, amin - bmax)


@numba.njit(cache=True)
def _axes_separation(
    a: np.ndarray, na: int, b: np.ndarray, nb: int, owner: np.ndarray, no: int
) -> float:
    """The largest projection gap of ``a`` and ``b`` over the normals of ``owner``'s edges."""
    best = -np.inf
    for i in range(no):
        j = (i + 1) % no
        ex = owner[j, 0] - owner[i, 0]
        ey = owner[j, 1] - owner[i, 1]
        length = np.hypot(ex, ey)
        if length == 0.0:
            continue
        best = max(best, _separation(a, na, b, nb, ey / length, -ex / length))
    return best


@numba.njit(cache=True)
def surely_apart(
    shapes: np.ndarray,
    pieces: np.ndarray,
    counts: np.ndarray,
    disc: np.ndarray,
    gap: float,
    slack: float,
) -> bool:
    """Whether every polygon ``shapes[s]`` is certainly more than ``gap`` (length) from every
    piece ``pieces[p, :counts[p]]`` and from the disc (x, y, r): some axis separates their
    projections by more than ``gap + slack`` (``slack`` covers rounding). A projection gap
    is a lower bound of the distance, so True is never wrong; False says nothing."""
    need = gap + slack
    for s in range(shapes.shape[0]):
        shape = shapes[s]
        ns = shape.shape[0]
        for p in range(pieces.shape[0]):
            count = counts[p]
            if count < 1:
                return False
            piece = pieces[p]
            sep = _axes_separation(shape, ns, piece, count, piece, count)
            if sep <= need:
                sep = max(sep, _axes_separation(shape, ns, piece, count, shape, ns))
            if sep <= need:
                return False
        # the disc: a vertex of the shape is at least this far along any axis from its centre
        cx, cy, r = disc[0], disc[1], disc[2]
        best = -np.inf
        for i in range(ns):
            j = (i + 1) % ns
            ex = shape[j, 0] - shape[i, 0]
            ey = shape[j, 1] - shape[i, 1]
            length = np.hypot(ex, ey)
            if length == 0.0:
                continue
            ux, uy = ey / length, -ex / length
            low = np.inf
            high = -np.inf
            for k in range(ns):
                v = shape[k, 0] * ux + shape[k, 1] * uy
                low = min(low, v)
                high = max(high, v)
            c = cx * ux + cy * uy
            best = max(best, max(low - c, c - high))
        for i in range(ns):
            ux, uy = shape[i, 0] - cx, shape[i, 1] - cy
            length = np.hypot(ux, uy)
            if length == 0.0:
                continue
            ux, uy = ux / length, uy / length
            low = np.inf
            for k in range(ns):
                low = min(low, (shape[k, 0] - cx) * ux + (shape[k, 1] - cy) * uy)
            best = max(best, low)
        if best - r <= need:
            return False
    return True


@numba.njit(cache=True)
def point_inside(segments: np.ndarray, px: float, py: float) -> int:
    """Whether the point is strictly inside the ring of edges ``(n, 2, 2)`` (1) or not (0),
    decided by crossings with certain orientations; :data:`UNSURE` where the point is on or
    near an edge (shapely decides: on the boundary is not inside)."""
    inside = False
    for i in range(segments.shape[0]):
        ax, ay = segments[i, 0, 0], segments[i, 0, 1]
        bx, by = segments[i, 1, 0], segments[i, 1, 1]
        near = min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)
        straddles = (ay > py) != (by > py)
        if not (near or straddles):
            continue
        turn, sure = _orientation(ax, ay, bx, by, px, py)
        if not sure or turn == 0:
            return UNSURE
        if straddles and (turn > 0) == (by > ay):
            inside = not inside
    return 1 if inside else 0


@numba.njit(cache=True)
def first_reached(
    segments: np.ndarray, px: float, py: float, r: float, skip: np.ndarray, start: int, tol: float
) -> tuple[int, int]:
    """The first edge ``i >= start`` not in ``skip`` within ``r`` of the point: ``(i,
    CROSSING)`` where its distance is certainly at most r (more than ``tol`` below),
    ``(i, UNSURE)`` where it is within ``tol`` of r (shapely decides), ``(-1, 0)`` if none."""
    for i in range(start, segments.shape[0]):
        if skip[i]:
            continue
        ax, ay = segments[i, 0, 0], segments[i, 0, 1]
        ex, ey = segments[i, 1, 0] - ax, segments[i, 1, 1] - ay
        wx, wy = px - ax, py - ay
        length2 = ex * ex + ey * ey
        t = 0.0 if length2 == 0.0 else min(1.0, max(0.0, (wx * ex + wy * ey) / length2))
        distance = np.hypot(wx - t * ex, wy - t * ey)
        if distance < r - tol:
            return i, CROSSING
        if distance <= r + tol:
            return i, UNSURE
    return -1, 0
