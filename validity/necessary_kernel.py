"""Compiled kernels of the necessary conditions (:mod:`validity.necessary`): a grid of the
outer free space, its distance transform, and flood fills over positions and yaw slices.

Every step errs on one side only, so that a design that can work always passes:

* ``free_mask``: a grid point is free when it lies in the outer free space (the nominal
  interior or a capsule round its boundary, outside the shrunk pin; ``validity.made_envelope``);
* ``distance_grid``: the exact Euclidean distance from each free grid point to the nearest
  grid point that is not free. That point lies outside the free space, so this is an *upper*
  bound of the free point's distance to the walls; anywhere else, the distance at the nearest
  grid point plus the gap to it is an upper bound too (distance is 1-Lipschitz);
* a *box* is a grid cell (``h x h`` round a grid point) times a yaw slice; it is kept when some
  pose in it could hold the part: each disc of radius ``w/2`` on the part's axis (all inside
  the part) is tested at the box's centre pose against that upper bound plus the farthest the
  disc's centre moves within the box (``h/sqrt(2)`` and ``|s| * slice/2`` for a disc ``s``
  along the axis). Any path of poses passes through a chain of boxes each sharing a point
  with the next (8 neighbours in the plane, 26 across slices), so a flood fill over kept
  boxes from the entry reaches the goal whenever the part can.

Arrays in, numbers or arrays out; grid point ``(i, j)`` is ``(x0 + i h, y0 + j h)``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_HALF_DIAGONAL = math.sqrt(0.5)  # the farthest a point of a unit cell is from its centre


@njit(cache=True)
def free_mask(
    outline: np.ndarray,
    capsules: np.ndarray,
    finger: np.ndarray,
    tip: np.ndarray,
    x0: float,
    y0: float,
    h: float,
    nx: int,
    ny: int,
) -> np.ndarray:
    """``(nx, ny)`` bool: grid points in the outer free space: inside the polygon ``outline
    (n, 2)`` (even-odd) or within ``capsules[k]`` of its segment ``k``, and not strictly inside
    the box ``finger`` (xmin, ymin, xmax, ymax) nor the disc ``tip`` (x, y, r)."""
    n = outline.shape[0]
    room = np.zeros((nx, ny), dtype=np.bool_)
    crossings = np.empty(n)
    for j in range(ny):
        y = y0 + j * h
        m = 0
        for k in range(n):
            ax, ay = outline[k, 0], outline[k, 1]
            bx, by = outline[(k + 1) % n, 0], outline[(k + 1) % n, 1]
            if (ay <= y < by) or (by <= y < ay):
                crossings[m] = ax + (y - ay) * (bx - ax) / (by - ay)
                m += 1
        xs = np.sort(crossings[:m])
        for p in range(0, m - 1, 2):
            i0 = max(0, math.ceil((xs[p] - x0) / h))
            i1 = min(nx - 1, math.floor((xs[p + 1] - x0) / h))
            for i in range(i0, i1 + 1):
                room[i, j] = True
    for k in range(n):
        ax, ay = outline[k, 0], outline[k, 1]
        bx, by = outline[(k + 1) % n, 0], outline[(k + 1) % n, 1]
        r = capsules[k]
        i0 = max(0, math.floor((min(ax, bx) - r - x0) / h))
        i1 = min(nx - 1, math.ceil((max(ax, bx) + r - x0) / h))
        j0 = max(0, math.floor((min(ay, by) - r - y0) / h))
        j1 = min(ny - 1, math.ceil((max(ay, by) + r - y0) / h))
        ex, ey = bx - ax, by - ay
        ll = ex * ex + ey * ey
        for i in range(i0, i1 + 1):
            px = x0 + i * h
            for j in range(j0, j1 + 1):
                if room[i, j]:
                    continue
                py = y0 + j * h
                t = 0.0
                if ll > 0.0:
                    t = min(1.0, max(0.0, ((px - ax) * ex + (py - ay) * ey) / ll))
                dx, dy = px - (ax + t * ex), py - (ay + t * ey)
                if dx * dx + dy * dy <= r * r:
                    room[i, j] = True
    for i in range(nx):
        px = x0 + i * h
        for j in range(ny):
            if not room[i, j]:
                continue
            py = y0 + j * h
            if finger[0] < px < finger[2] and finger[1] < py < finger[3]:
                room[i, j] = False
            elif (px - tip[0]) ** 2 + (py - tip[1]) ** 2 < tip[2] * tip[2]:
                room[i, j] = False
    return room


@njit(cache=True)
def _squared_transform_1d(f: np.ndarray, v: np.ndarray, z: np.ndarray, out: np.ndarray) -> None:
    """Felzenszwalb and Huttenlocher's lower envelope of parabolas: ``out[q] = min_p
    (q - p)^2 + f[p]`` (grid steps; ``f`` holds integers, exact in floating point)."""
    n = f.shape[0]
    k = 0
    v[0] = 0
    z[0], z[1] = -np.inf, np.inf
    for q in range(1, n):
        p = v[k]
        s = ((f[q] + q * q) - (f[p] + p * p)) / (2.0 * (q - p))
        while s <= z[k]:
            k -= 1
            p = v[k]
            s = ((f[q] + q * q) - (f[p] + p * p)) / (2.0 * (q - p))
        k += 1
        v[k] = q
        z[k] = s
        z[k + 1] = np.inf
    k = 0
    for q in range(n):
        while z[k + 1] < q:
            k += 1
        p = v[k]
        out[q] = (q - p) * (q - p) + f[p]


@njit(cache=True)
def distance_grid(room: np.ndarray, h: float) -> np.ndarray:
    """``(nx, ny)``: the distance (length) from each grid point to the nearest grid point
    that is not in ``room`` (0 on those), by the exact squared Euclidean transform; ``room``
    must leave some grid point out."""
    nx, ny = room.shape
    far = float(nx * nx + ny * ny + 1)  # beyond any squared distance on the grid
    size = max(nx, ny)
    v = np.zeros(size, dtype=np.int64)
    z = np.empty(size + 1)
    g = np.empty((nx, ny))
    column = np.empty(ny)
    out_col = np.empty(ny)
    for i in range(nx):
        for j in range(ny):
            column[j] = far if room[i, j] else 0.0
        _squared_transform_1d(column, v, z, out_col)
        g[i, :] = out_col
    row = np.empty(nx)
    out_row = np.empty(nx)
    dist = np.empty((nx, ny))
    for j in range(ny):
        row[:] = g[:, j]
        _squared_transform_1d(row, v, z, out_row)
        for i in range(nx):
            dist[i, j] = math.sqrt(min(out_row[i], far)) * h
    return dist


@njit(cache=True)
def _upper(dist: np.ndarray, x0: float, y0: float, h: float, px: float, py: float) -> float:
    """An upper bound of the distance from (px, py) to the walls: the nearest grid point's
    plus the gap to it."""
    nx, ny = dist.shape
    i = min(nx - 1, max(0, round((px - x0) / h)))
    j = min(ny - 1, max(0, round((py - y0) / h)))
    return dist[i, j] + math.hypot(px - (x0 + i * h), py - (y0 + j * h))


@njit(cache=True)
def pose_box_fits(
    dist: np.ndarray,
    x0: float,
    y0: float,
    h: float,
    i: int,
    j: int,
    yaw: float,
    half_slice: float,
    axis: np.ndarray,
    radius: float,
) -> bool:
    """Whether some pose within cell ``(i, j)`` and ``yaw +- half_slice`` may hold the part
    whose axis discs (radius ``radius``) sit at offsets ``axis`` along its yaw (False only
    when none can)."""
    px, py = x0 + i * h, y0 + j * h
    c, s = math.cos(yaw), math.sin(yaw)
    for k in range(axis.shape[0]):
        a = axis[k]
        slack = _HALF_DIAGONAL * h + abs(a) * half_slice
        if _upper(dist, x0, y0, h, px + a * c, py + a * s) + slack < radius:
            return False
    return True


@njit(cache=True)
def corridor_flood(
    dist: np.ndarray,
    x0: float,
    y0: float,
    h: float,
    radius: float,
    entry: np.ndarray,
    y_goal: float,
) -> tuple[bool, np.ndarray]:
    """``(reaches, reached)``: whether a disc of ``radius`` can get from the entry disc
    ``entry`` (x, y, r of its possible centres) to a centre at or below ``y_goal``, and the
    cells it reaches (8-connected flood over the cells that may hold it)."""
    nx, ny = dist.shape
    keep = dist + _HALF_DIAGONAL * h >= radius
    reached = np.zeros((nx, ny), dtype=np.bool_)
    queue = np.empty(nx * ny, dtype=np.int64)
    head = tail = 0
    reach = entry[2] + _HALF_DIAGONAL * h
    for i in range(nx):
        for j in range(ny):
            if keep[i, j] and math.hypot(x0 + i * h - entry[0], y0 + j * h - entry[1]) <= reach:
                reached[i, j] = True
                queue[tail] = i * ny + j
                tail += 1
    found = False
    while head < tail:
        cell = queue[head]
        head += 1
        i, j = cell // ny, cell % ny
        if y0 + j * h - 0.5 * h <= y_goal:
            found = True
        for di in range(-1, 2):
            for dj in range(-1, 2):
                a, b = i + di, j + dj
                if 0 <= a < nx and 0 <= b < ny and keep[a, b] and not reached[a, b]:
                    reached[a, b] = True
                    queue[tail] = a * ny + b
                    tail += 1
    return found, reached


@njit(cache=True)
def turn_room(
    dist: np.ndarray,
    x0: float,
    y0: float,
    h: float,
    reached: np.ndarray,
    axis: np.ndarray,
    radius: float,
) -> int:
    """How many ``reached`` cells may hold the part horizontal (yaw 0; the part is symmetric
    end for end, so yaw pi is the same shape)."""
    count = 0
    nx, ny = dist.shape
    for i in range(nx):
        for j in range(ny):
            if reached[i, j] and pose_box_fits(dist, x0, y0, h, i, j, 0.0, 0.0, axis, radius):
                count += 1
    return count


@njit(cache=True)
def _box_fits(
    fits: np.ndarray,
    dist: np.ndarray,
    x0: float,
    y0: float,
    h: float,
    k: int,
    i: int,
    j: int,
    width: float,
    axis: np.ndarray,
    radius: float,
) -> bool:
    """:func:`pose_box_fits` of slice ``k``, remembered in ``fits`` (0 not yet asked, 1 fits,
    2 does not; slice ``k`` and ``k + n/2`` hold the same shape, the part being symmetric)."""
    shape = k % fits.shape[0]
    if fits[shape, i, j] == 0:
        ok = pose_box_fits(dist, x0, y0, h, i, j, (k + 0.5) * width, 0.5 * width, axis, radius)
        fits[shape, i, j] = 1 if ok else 2
    return fits[shape, i, j] == 1


@njit(cache=True)
def sliced_flood(
    dist: np.ndarray,
    x0: float,
    y0: float,
    h: float,
    axis: np.ndarray,
    radius: float,
    entry: np.ndarray,
    entry_slices: np.ndarray,
    goal_slices: np.ndarray,
    y_goal: float,
    reached: np.ndarray,
    fits: np.ndarray,
) -> bool:
    """Whether the part can get from the entry (centre in the disc ``entry``, yaw in a slice
    flagged by ``entry_slices``) to a goal box (centre at or below ``y_goal``, yaw in a slice
    flagged by ``goal_slices``) through boxes that may hold it: a 26-connected search over
    the cells times ``n = len(entry_slices)`` yaw slices of ``[0, 2 pi)``, slice ``k``
    covering ``[k, k + 1] * 2 pi / n``. Only cells of ``reached`` (the corridor's flood, which
    holds every cell a reachable pose's centre can be in) are searched; ``fits`` (``(n // 2,
    nx, ny)`` int8, zeros, for even ``n``; else ``(n, nx, ny)``) remembers each box's test
    and may be shared by calls on the same grid. Depth first, downward first: a design that
    passes is found long before the search is exhausted."""
    nx, ny = dist.shape
    n = entry_slices.shape[0]
    width = 2.0 * math.pi / n
    seen = np.zeros((n, nx, ny), dtype=np.bool_)
    stack = np.empty(n * nx * ny, dtype=np.int64)
    top = 0
    reach = entry[2] + _HALF_DIAGONAL * h
    for k in range(n):
        if not entry_slices[k]:
            continue
        for i in range(nx):
            for j in range(ny):
                if not reached[i, j]:
                    continue
                if math.hypot(x0 + i * h - entry[0], y0 + j * h - entry[1]) > reach:
                    continue
                seen[k, i, j] = True
                if _box_fits(fits, dist, x0, y0, h, k, i, j, width, axis, radius):
                    stack[top] = (k * nx + i) * ny + j
                    top += 1
    while top > 0:
        top -= 1
        box = stack[top]
        k, rest = box // (nx * ny), box % (nx * ny)
        i, j = rest // ny, rest % ny
        if goal_slices[k] and y0 + j * h - 0.5 * h <= y_goal:
            return True
        for dj in range(1, -2, -1):  # pushed last, searched first: downward
            b = j + dj
            if b < 0 or b >= ny:
                continue
            for di in range(-1, 2):
                a = i + di
                if a < 0 or a >= nx or not reached[a, b]:
                    continue
                for dk in range(-1, 2):
                    kk = (k + dk) % n
                    if seen[kk, a, b]:
                        continue
                    seen[kk, a, b] = True
                    if _box_fits(fits, dist, x0, y0, h, kk, a, b, width, axis, radius):
                        stack[top] = (kk * nx + a) * ny + b
                        top += 1
    return False
