"""Candidate contacts between the part and the static obstacles, for the contact levels.

A contact is a point of the part with a signed gap psi_n to an obstacle (negative: penetration
depth), the unit normal n along which the obstacle pushes the part, and the tangent
t = (-n_y, n_x). Contacts are reported for every feature pair closer than a margin, so the
time stepper of Eq. 7 sees contacts "in or about to be in contact" and its psi_n / h term lets
each one close at most its gap in a step.

The part and the polygons are convex, so two of them first touch vertex-to-edge (or
vertex-to-vertex): the candidates are each part corner against each nearby polygon, each
polygon corner against the part, and each disc centre against the part. A part corner
strictly inside the solid is one contact with its depth in the whole solid (the distance to the
nearest surface segment, :func:`solid_depth`), not one per piece it lies in. Signed distances
use the same separating-axis rule as :mod:`validity.geometry_kernel`, so both levels agree on
what penetrates.

Which feature pairs are contacts (issue 26) is decided from the geometry of both shapes, as
Box2D's polygon collider does (Catto, ``b2CollidePolygons``: a separating-axis reference face,
and points kept only within its side planes), with the separating-axis test of the part and
each nearby piece asked only as far as a rule needs it (:func:`_overlap_below`):

- a vertex in front of a face, within the margin, is a contact of that face only when its
  nearest point lies further from the face's ends than the pair already overlaps
  (:func:`_keeps`). Otherwise the vertex lies in the plane of the face beside it, which is
  sliding over it: a peg resting on a slab, its bottom face a hair into the slab, has the
  slab's end vertex in front of its end face, and pairing the two stopped the slide (the
  speculative contacts of the paper's psi_n / h see gaps before they close, so a wrong
  pairing acts before any overlap; pymunk and MuJoCo, which make contacts only on overlap,
  never had it). Ghost collisions at internal seams are the same phenomenon (Catto, "Ghost
  Collisions", 2020; Chipmunk's segment neighbours); the seams of one solid are handled by the
  surface and corner flags below;
- vertex against vertex is a contact only for the part's own corners, and only while the pair
  is apart (the obstacle's corners would repeat it; once the pair overlaps, the corner lies in
  the plane of a face sliding over the other shape);
- an overlap deeper than any vertex of either shape lies inside the other (two corners that
  passed each other in one step, a part straddling a thin piece: vertex tests see nothing or
  too little) gets one contact along the axis of least penetration over the part's edges
  and the piece's surface edges, at the deepest vertex of the other shape, with that overlap
  as its depth (:func:`_add_axis_contact`): the separating-axis theorem's penetration depth,
  exact for convex pairs (Ericson, *Real-Time Collision Detection*, 2005, section 5.2.1).

- a point whose nearest feature of a piece is a seam (a face another piece covers) is in
  front of the piece's surface faces that begin beyond the cover: the nearest such face
  within the margin is its contact, at the distance to the face's line
  (:func:`surface_in_front`), and so is it for a corner inside another piece: a corner
  sliding down a ramp, or inside a wall's face, into the concave corner where it meets a
  floor keeps the floor ahead of it (issue 35: it entered the floor by h times its speed);
- a flat joint (a vertex where the face continues on a neighbouring piece) gives the
  distance to the face's line only on the joint's own normal: off it, the neighbour's
  feature is the nearer one (issue 35: the cup's base continued its outer face beyond the
  cup's outer corner and reported pin B 8.5e-3 deep where it was 2.8e-6 clear).

``FEATURE_SLOP`` (1e-6 length) is the depth below which two features are not told apart: a
feature of the pair thinner than that is not resolved, and a vertex that far from the other
shape or nearer is in contact, whichever feature it is nearest (stress case 11/8546: a corner
touching the floor just where a ramp leaves it kept only the ramp's normal and sank 0.042 in
one coarse step). A candidate within the margin that is not kept still bounds the clearance
the stepper uses to skip contact searches. Arrays in, numbers out; compiled with numba.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from validity.geometry_kernel import _box_gap, _box_of, _edge_normal, polygon_aabbs
from validity.leaf_kernel import leaf_kernel

MAX_CONTACTS = 12  # a planar convex part touches at most a few features; deeper ones are kept
_TINY = 1e-14
_ALL_TRUE = np.ones(1, dtype=np.bool_)  # read-only default: every edge and vertex is real
_SEAM_PROBE = 1e-7  # how far past a vertex (length) the solid is probed for a flat joint
FEATURE_SLOP = 1e-6  # depth (length) below which two features of a pair are not told apart


@leaf_kernel
def _contains(b: np.ndarray, nb: int, px: float, py: float) -> bool:
    """p inside or on the convex CCW polygon b[:nb]."""
    for i in range(nb):
        nx, ny, ok = _edge_normal(b, i, nb)
        if ok and nx * (px - b[i, 0]) + ny * (py - b[i, 1]) > 0.0:
            return False
    return True


@leaf_kernel
def point_polygon_feature(
    px: float,
    py: float,
    b: np.ndarray,
    nb: int,
    cutoff: float = np.inf,
    surface: np.ndarray = _ALL_TRUE,
    corners: np.ndarray = _ALL_TRUE,
) -> tuple[float, float, float, float, float, bool, bool, int]:
    """Signed distance from point p to the convex CCW polygon b[:nb], with its nearest feature.

    Returns ``(gap, nx, ny, cx, cy, at_vertex, hidden, edge)``: the signed distance (negative
    inside: the depth to the nearest surface edge line), the unit outward normal of b that
    pushes p out, the nearest point c of b's boundary, whether c is a vertex of b, whether
    the nearest feature is hidden inside the solid that b is a piece of, and the edge whose
    line or segment gave the gap (for a vertex: an edge ending there). ``surface[i]`` says
    whether edge i (from vertex i to i + 1) is a real surface and ``corners[k]`` whether
    vertex k is a corner (not a flat joint) of the solid: a seam never gives the normal of a
    point inside, and a point outside whose nearest feature is a seam or a flat joint is
    ``hidden`` (the neighbouring piece gives the real contact; this one would push along the
    surface). When p is at least ``cutoff`` outside an edge line, that separation (a lower
    bound of the distance) is returned as the gap at once.
    """
    inside, in_nx, in_ny, in_i = -np.inf, 0.0, 0.0, -1
    depth, d_nx, d_ny, d_i = -np.inf, 0.0, 0.0, -1
    last_s, last_c = surface.shape[0] - 1, corners.shape[0] - 1
    for i in range(nb):
        nx, ny, ok = _edge_normal(b, i, nb)
        if ok:
            d = nx * (px - b[i, 0]) + ny * (py - b[i, 1])
            if d > inside:
                inside, in_nx, in_ny, in_i = d, nx, ny, i
            if d > depth and surface[min(i, last_s)]:
                depth, d_nx, d_ny, d_i = d, nx, ny, i
    if inside >= cutoff and in_i >= 0:
        return inside, in_nx, in_ny, px - inside * in_nx, py - inside * in_ny, False, False, in_i
    if inside <= 0.0 and d_i >= 0:
        return depth, d_nx, d_ny, px - depth * d_nx, py - depth * d_ny, False, False, d_i
    best, cx, cy, vertex, hidden, joint, edge = np.inf, px, py, False, False, -1, 0
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
            best, cx, cy, vertex, edge = d, qx, qy, (t <= 0.0 or t >= 1.0), i
            k = i if t <= 0.0 else j
            joint = k if vertex and not corners[min(k, last_c)] else -1
            hidden = not vertex and not surface[min(i, last_s)]
    if joint >= 0:  # a flat joint: the distance to the surface line through it
        for i in ((joint - 1) % nb, joint):
            nx, ny, ok = _edge_normal(b, i, nb)
            if ok and surface[min(i, last_s)]:
                gap = nx * (px - b[joint, 0]) + ny * (py - b[joint, 1])
                along = abs(ny * (px - b[joint, 0]) - nx * (py - b[joint, 1]))
                if gap >= 0.0 and along <= FEATURE_SLOP:
                    return gap, nx, ny, px - gap * nx, py - gap * ny, False, False, i
                break  # off the joint's normal: the neighbour's own feature is nearer
        hidden = True
    if best > _TINY and not vertex:  # the edge's own normal: exact even for a tiny gap
        nx, ny, _ = _edge_normal(b, edge, nb)
        return best, nx, ny, cx, cy, vertex, hidden, edge
    if best > _TINY:
        return best, (px - cx) / best, (py - cy) / best, cx, cy, vertex, hidden, edge
    return best, in_nx, in_ny, cx, cy, vertex, hidden, in_i  # on the boundary: the edge's normal


@leaf_kernel
def surface_in_front(
    px: float, py: float, b: np.ndarray, nb: int, reach: float, surface: np.ndarray
) -> tuple[float, float, float, int]:
    """The surface face of the convex piece b[:nb] that p is in front of, whose segment lies
    within ``reach`` of p (the nearest such), as ``(gap, nx, ny, edge)``: the distance from p
    to the face's line and its outward normal (edge -1 and an infinite gap when there is
    none).

    A point whose nearest feature of b is a seam, or that lies inside another piece, can
    still be about to cross b's surface: a corner sliding down a ramp into the concave corner
    where the ramp meets a floor is nearest the floor's face under the ramp (a seam), and the
    floor's surface begins at the ramp's foot, within a step of it (issue 35: such a corner
    entered the floor by h times its speed). The face's line is where b's solid begins there:
    b lies behind it along the whole face, so keeping p in front of it is a true constraint,
    never stronger than the solid, and the linearised contact of Eq. 7 needs no more."""
    best, gap, nx, ny, edge = reach, np.inf, 0.0, 0.0, -1
    last_s = surface.shape[0] - 1
    for i in range(nb):
        if not surface[min(i, last_s)]:
            continue
        ex_, ey_, ok = _edge_normal(b, i, nb)
        if not ok:
            continue
        d = ex_ * (px - b[i, 0]) + ey_ * (py - b[i, 1])
        if d < 0.0:
            continue
        j = (i + 1) % nb
        ax, ay = b[i, 0], b[i, 1]
        ex, ey = b[j, 0] - ax, b[j, 1] - ay
        t = min(1.0, max(0.0, ((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey)))
        seg = math.hypot(px - ax - t * ex, py - ay - t * ey)
        if seg < best:
            best, gap, nx, ny, edge = seg, d, ex_, ey_, i
    return gap, nx, ny, edge


@leaf_kernel
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


@leaf_kernel
def _solid(verts: np.ndarray, counts: np.ndarray, px: float, py: float) -> bool:
    for q in range(verts.shape[0]):
        if _contains(verts[q], counts[q], px, py):
            return True
    return False


@njit(cache=True)
def corner_vertices(verts: np.ndarray, counts: np.ndarray, surface: np.ndarray) -> np.ndarray:
    """``(P, K)``: False where vertex k of polygon p only joins two pieces along a straight
    surface (a surface edge ends there and the solid continues along its line in another
    piece), True elsewhere. Such a joint is no corner a part can touch; a contact of its own
    would, with the part sliding over it, push along the surface: a ghost that stops a slide.
    ``surface (P, K)`` marks the real surface edges (:mod:`validity.solid_surface`).
    """
    P, K = verts.shape[0], verts.shape[1]
    out = np.ones((P, K), dtype=np.bool_)
    for p in range(P):
        n = counts[p]
        for k in range(n):
            for i, toward in ((k, 1), ((k - 1) % n, -1)):  # the edges leaving and entering k
                nx, ny, ok = _edge_normal(verts[p], i, n)
                if not ok or not surface[p, i]:
                    continue
                j = (i + 1) % n
                tx, ty = verts[p, j, 0] - verts[p, i, 0], verts[p, j, 1] - verts[p, i, 1]
                ll = math.hypot(tx, ty)
                tx, ty = -toward * tx / ll, -toward * ty / ll  # along the line, beyond k
                bx = verts[p, k, 0] + _SEAM_PROBE * tx
                by = verts[p, k, 1] + _SEAM_PROBE * ty
                below = _solid(
                    verts, counts, bx - 1e-3 * _SEAM_PROBE * nx, by - 1e-3 * _SEAM_PROBE * ny
                )
                above = _solid(
                    verts, counts, bx + 1e-3 * _SEAM_PROBE * nx, by + 1e-3 * _SEAM_PROBE * ny
                )
                if below and not above:
                    out[p, k] = False
    return out


@leaf_kernel
def _strictly_inside(verts: np.ndarray, counts: np.ndarray, aabbs: np.ndarray, px, py) -> bool:
    """p strictly inside (by more than round-off) one of the polygons."""
    for q in range(verts.shape[0]):  # indexed, not sliced: a view per piece costs more here
        if px <= aabbs[q, 0] or py <= aabbs[q, 1] or px >= aabbs[q, 2] or py >= aabbs[q, 3]:
            continue
        nb = counts[q]
        inside = True
        for i in range(nb):
            j = (i + 1) % nb
            ex, ey = verts[q, j, 0] - verts[q, i, 0], verts[q, j, 1] - verts[q, i, 1]
            cross = ey * (px - verts[q, i, 0]) - ex * (py - verts[q, i, 1])  # |e| x distance
            if cross > -_TINY * (abs(ex) + abs(ey)) and ex * ex + ey * ey > _TINY * _TINY:
                inside = False  # outside, on, or within round-off of edge i's line
                break
        if inside:
            return True
    return False


@leaf_kernel
def solid_depth(
    px: float,
    py: float,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    surface: np.ndarray,
    circles: np.ndarray,
) -> tuple[float, float, float]:
    """``(depth, nx, ny)`` of a point p inside the solid: its distance to the nearest point c
    of the solid's surface (every surface sub-edge of :mod:`validity.solid_surface` as a
    segment, and each disc's circle where its point nearest p is not inside another piece:
    together they are the boundary of the union) and the unit normal (c - p) / |c - p| that
    pushes p out. The depth in the whole solid, not in the one piece p lies in: a corner
    inside one piece next to a seam is nearest the surface of the piece beyond the seam, and
    the nearest surface line of its own piece may be far (stress case 0/1682) or face into
    the neighbour."""
    best, nx, ny = np.inf, 0.0, 0.0
    for q in range(verts.shape[0]):
        box = aabbs[q]
        gx = max(box[0] - px, 0.0, px - box[2])
        gy = max(box[1] - py, 0.0, py - box[3])
        if math.hypot(gx, gy) >= best:
            continue
        b, nb = verts[q], counts[q]
        for i in range(nb):
            if not surface[q, i]:
                continue
            j = (i + 1) % nb
            ax, ay = b[i, 0], b[i, 1]
            ex, ey = b[j, 0] - ax, b[j, 1] - ay
            ll = ex * ex + ey * ey
            t = 0.0
            if ll > _TINY:
                t = min(1.0, max(0.0, ((px - ax) * ex + (py - ay) * ey) / ll))
            cx, cy = ax + t * ex - px, ay + t * ey - py
            d = math.hypot(cx, cy)
            if d < best:
                best = d
                if 0.0 < t < 1.0 or d <= _TINY:  # the edge's outward normal: exact at any depth
                    nx, ny, _ = _edge_normal(b, i, nb)
                else:  # nearest a corner of the surface: out towards it
                    nx, ny = cx / d, cy / d
    for q in range(circles.shape[0]):
        ox, oy, r = circles[q, 0], circles[q, 1], circles[q, 2]
        dx, dy = px - ox, py - oy
        dist = math.hypot(dx, dy)
        if dist <= _TINY or abs(r - dist) >= best:
            continue
        cx, cy = ox + r * dx / dist, oy + r * dy / dist
        if _strictly_inside(verts, counts, aabbs, cx, cy) or _in_other_disc(circles, q, cx, cy):
            continue
        best = abs(r - dist)
        sign = 1.0 if dist < r else -1.0  # inside the disc: out along the radius
        nx, ny = sign * dx / dist, sign * dy / dist
    return best, nx, ny


@leaf_kernel
def _in_other_disc(circles: np.ndarray, skip: int, px: float, py: float) -> bool:
    for q in range(circles.shape[0]):
        if q != skip and math.hypot(px - circles[q, 0], py - circles[q, 1]) < circles[q, 2] - _TINY:
            return True
    return False


@leaf_kernel
def _run_end(a: np.ndarray, na: int, edge: int, step: int) -> int:
    """The vertex where the straight run of edges through ``edge`` ends, going forward
    (``step`` 1: the run's last vertex) or back (-1: its first): a split edge's collinear
    pieces are one face."""
    j = (edge + 1) % na
    ex, ey = a[j, 0] - a[edge, 0], a[j, 1] - a[edge, 1]
    i = edge
    for _ in range(na - 1):
        k = (i + step) % na
        m = (k + 1) % na
        fx, fy = a[m, 0] - a[k, 0], a[m, 1] - a[k, 1]
        cross, dot = ex * fy - ey * fx, ex * fx + ey * fy
        if fx * fx + fy * fy > _TINY * _TINY and (dot <= 0.0 or cross * cross > 1e-24 * dot * dot):
            break  # turns (a zero-length padding edge is part of the run)
        i = k
    return (i + 1) % na if step == 1 else i


@leaf_kernel
def _reaches_behind(a: np.ndarray, na: int, c: np.ndarray, nc: int, depth: float) -> bool:
    """Whether, along every edge normal of the convex polygon a[:na], some vertex of c[:nc]
    lies at least ``depth`` (>= 0) behind the edge's line. Stops an axis at the first such
    vertex; no square root (the edge vector's length scales both sides)."""
    for i in range(na):
        j = (i + 1) % na
        ex, ey = a[j, 0] - a[i, 0], a[j, 1] - a[i, 1]
        ll = ex * ex + ey * ey
        if ll <= _TINY * _TINY:
            continue
        reach = False
        for k in range(nc):
            s = ey * (c[k, 0] - a[i, 0]) - ex * (c[k, 1] - a[i, 1])  # |e| times the distance
            if s <= 0.0 and s * s >= depth * depth * ll:
                reach = True
                break
        if not reach:
            return False
    return True


@leaf_kernel
def _overlap_below(world, n, b, nb, depth) -> bool:
    """Whether the part and the convex piece b[:nb] overlap by less than ``depth`` (length) in
    the separating-axis sense: along some edge normal of either shape the other reaches less
    than ``depth`` behind the edge's line. Most questions end on the part's own four axes."""
    return not (_reaches_behind(world, n, b, nb, depth) and _reaches_behind(b, nb, world, n, depth))


@leaf_kernel
def _keeps(
    a: np.ndarray,
    na: int,
    edge: int,
    cx: float,
    cy: float,
    at_vertex: bool,
    vertex_pairs: bool,
    world: np.ndarray,
    n: int,
    b: np.ndarray,
    nb: int,
    boxes_apart: bool,
) -> bool:
    """Whether a vertex outside a (the part or the piece b), whose nearest point of a is c (on
    the face through ``edge``, or a's vertex), is a contact of the pair, given how far the
    pair already overlaps (the separating-axis depth; 0 when apart).

    A face contact needs c further from the face's ends than the pair overlaps: a vertex
    within the overlap of a face's end lies in the plane of the face beside it, which slides
    over it (the slab's end vertex under a peg's bottom face, paired with the peg's end face,
    stopped the slide). Box2D keeps a point only inside the reference face's side planes for
    the same reason. Nearer the end than that, or at a's vertex, the pair is vertex against
    vertex: a contact only for the part's own corners (``vertex_pairs``; the obstacle's
    corners would repeat them) and only while the shapes are apart; once they overlap, the
    corner lies in the plane of a face that slides over the other shape. ``boxes_apart``:
    the bounding boxes of the pair do not meet (so neither do the shapes)."""
    apart = boxes_apart or _overlap_below(world, n, b, nb, FEATURE_SLOP)
    if not at_vertex:
        j = (edge + 1) % na
        own = min(
            (cx - a[edge, 0]) ** 2 + (cy - a[edge, 1]) ** 2,
            (cx - a[j, 0]) ** 2 + (cy - a[j, 1]) ** 2,
        )
        if apart and own > FEATURE_SLOP * FEATURE_SLOP:  # the face's run holds its own edge
            return True
        first, last = _run_end(a, na, edge, -1), _run_end(a, na, edge, 1)
        inset = math.sqrt(
            min(
                (cx - a[first, 0]) ** 2 + (cy - a[first, 1]) ** 2,
                (cx - a[last, 0]) ** 2 + (cy - a[last, 1]) ** 2,
            )
        )
        if inset > FEATURE_SLOP and (
            apart or _overlap_below(world, n, b, nb, inset - FEATURE_SLOP)
        ):
            return True
    return vertex_pairs and apart


@leaf_kernel
def _depth_in(b: np.ndarray, nb: int, px: float, py: float) -> float:
    """Signed distance of p to the edge lines of the convex polygon b[:nb] (the largest one):
    negative inside, minus p's depth in b."""
    out = -np.inf
    for i in range(nb):
        nx, ny, ok = _edge_normal(b, i, nb)
        if ok:
            out = max(out, nx * (px - b[i, 0]) + ny * (py - b[i, 1]))
    return out


@leaf_kernel
def _add_axis_contact(world, n, b, nb, part_surface, surface, contacts, nc) -> int:
    """The contact of an overlap deeper than any vertex of either shape lies inside the other
    (two corners passed each other, or the part straddles a thin piece): along the
    separating axis of least penetration (the surface edges of the part and of the piece), at
    the deepest vertex of the other shape, with the overlap as its depth."""
    best, side, axis = -np.inf, 0, -1
    last, last_p = surface.shape[0] - 1, part_surface.shape[0] - 1
    for which, a, na, c, nc_ in ((0, world, n, b, nb), (1, b, nb, world, n)):
        for i in range(na):
            nx, ny, ok = _edge_normal(a, i, na)
            real = part_surface[min(i, last_p)] if which == 0 else surface[min(i, last)]
            if not ok or not real:
                continue
            low = np.inf
            for k in range(nc_):
                low = min(low, nx * (c[k, 0] - a[i, 0]) + ny * (c[k, 1] - a[i, 1]))
            if low > best:
                best, side, axis = low, which, i
    if axis < 0 or best >= 0.0:
        return nc
    if side == 1:  # the piece's edge pushes the part's deepest corner out
        nx, ny, _ = _edge_normal(b, axis, nb)
        k, low = 0, np.inf
        for m in range(n):
            d = nx * (world[m, 0] - b[axis, 0]) + ny * (world[m, 1] - b[axis, 1])
            if d < low:
                k, low = m, d
        return _add(contacts, nc, best, nx, ny, world[k, 0], world[k, 1])
    nx, ny, _ = _edge_normal(world, axis, n)  # the piece's deepest vertex pushes the part's edge
    k, low = 0, np.inf
    for m in range(nb):
        d = nx * (b[m, 0] - world[axis, 0]) + ny * (b[m, 1] - world[axis, 1])
        if d < low:
            k, low = m, d
    return _add(contacts, nc, best, -nx, -ny, b[k, 0] - low * nx, b[k, 1] - low * ny)


@leaf_kernel
def find_contacts(
    world: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    surface: np.ndarray,
    corners: np.ndarray,
    margin: float,
    contacts: np.ndarray,
    nc: int = 0,
    part_surface: np.ndarray = _ALL_TRUE,
    part_corners: np.ndarray = _ALL_TRUE,
) -> tuple[int, float]:
    """Contacts of the placed convex part (or part piece) ``world (n, 2)`` with gap below
    ``margin``, appended after the ``nc`` rows already in ``contacts``.

    Writes rows ``(gap, nx, ny, px, py)`` into ``contacts (MAX_CONTACTS, 5)``: the point p is
    on the part and n points from the obstacle into the part. Returns ``(count, clear)``:
    ``clear`` is a lower bound on the distance to every obstacle that gave no contact (inf when
    there is none), so a caller with no contacts knows how far the part may move before one
    can appear. ``surface (P, K)`` marks the polygons' real surface edges
    (:mod:`validity.solid_surface`), ``corners (P, K)`` their contact corners
    (:func:`corner_vertices`). ``part_surface (n,)`` and ``part_corners (n,)`` are the same
    flags for a piece of a composite part (its seams with the part's other pieces are no
    surface, its flat joints no corners; default: every edge and vertex is real). Broad phase:
    obstacles whose bounding box is ``margin`` or more away are bounded by that box gap and
    not tested further.
    """
    n = world.shape[0]
    x0, y0, x1, y1 = _box_of(world)
    clear = np.inf
    last_pc = part_corners.shape[0] - 1
    buried = 0  # bit k: part corner k is strictly inside the solid (parts have < 63 corners)
    for k in range(n):
        if not part_corners[min(k, last_pc)]:
            continue
        if _strictly_inside(verts, counts, aabbs, world[k, 0], world[k, 1]):
            buried |= 1 << k
            depth, nx, ny = solid_depth(
                world[k, 0], world[k, 1], verts, counts, aabbs, surface, circles
            )
            if depth < np.inf:
                nc = _add(contacts, nc, -depth, nx, ny, world[k, 0], world[k, 1])
    for p in range(verts.shape[0]):
        gap = _box_gap(x0, y0, x1, y1, aabbs[p])
        if gap >= margin:
            clear = min(clear, gap)
            continue
        b, nb = verts[p], counts[p]
        b_surface, b_corners = surface[p], corners[p]  # one view each, not one per vertex
        explained = 0.0  # the deepest a vertex of either shape lies inside the other
        nearest = np.inf
        for k in range(n):
            is_corner = part_corners[min(k, last_pc)]
            if buried >> k & 1 and not (is_corner and gap < margin):
                continue
            px, py = world[k, 0], world[k, 1]
            d, nx, ny, cx, cy, at_vertex, hidden, edge = point_polygon_feature(
                px, py, b, nb, margin, b_surface, b_corners
            )
            if buried >> k & 1:  # its depth is the solid's; here only a face it may cross
                if d <= 0.0:
                    continue
            else:
                nearest = min(nearest, d)
                explained = max(explained, -d)
            if d < margin and hidden and is_corner:
                g, gnx, gny, e = surface_in_front(px, py, b, nb, margin, b_surface)
                if e >= 0:
                    d, nx, ny, at_vertex, hidden, edge = g, gnx, gny, False, False, e
                    cx, cy = px - g * gnx, py - g * gny
            if (
                d < margin
                and not hidden
                and is_corner
                and (
                    d <= FEATURE_SLOP
                    or _keeps(b, nb, edge, cx, cy, at_vertex, True, world, n, b, nb, gap > 0.0)
                )
            ):
                nc = _add(contacts, nc, d, nx, ny, px, py)
        for j in range(nb):
            if not b_corners[j]:
                continue
            d, nx, ny, cx, cy, at_vertex, hidden, edge = point_polygon_feature(
                b[j, 0], b[j, 1], world, n, margin, part_surface, part_corners
            )
            nearest = min(nearest, d)
            explained = max(explained, -d)
            if d < margin and hidden:
                g, gnx, gny, e = surface_in_front(b[j, 0], b[j, 1], world, n, margin, part_surface)
                if e >= 0:
                    d, nx, ny, at_vertex, hidden, edge = g, gnx, gny, False, False, e
                    cx, cy = b[j, 0] - g * gnx, b[j, 1] - g * gny
            if (d < margin and not hidden) and (
                d <= FEATURE_SLOP
                or _keeps(world, n, edge, cx, cy, at_vertex, False, world, n, b, nb, gap > 0.0)
            ):
                nc = _add(contacts, nc, d, -nx, -ny, cx, cy)
        # An overlap deeper than every vertex inside the other shape: asked first without the
        # buried corners' depths in this piece, and never when the boxes are apart.
        if gap <= 0.0 and not _overlap_below(world, n, b, nb, explained + FEATURE_SLOP):
            for k in range(n):
                if buried >> k & 1:
                    explained = max(explained, -_depth_in(b, nb, world[k, 0], world[k, 1]))
            if not _overlap_below(world, n, b, nb, explained + FEATURE_SLOP):
                nc = _add_axis_contact(world, n, b, nb, part_surface, b_surface, contacts, nc)
        clear = min(clear, nearest)  # below the margin too when a candidate was not kept
    for q in range(circles.shape[0]):
        ox, oy, r = circles[q, 0], circles[q, 1], circles[q, 2]
        gx = max(x0 - ox, 0.0, ox - x1)
        gy = max(y0 - oy, 0.0, oy - y1)
        gap = math.hypot(gx, gy) - r
        if gap >= margin:
            clear = min(clear, gap)
            continue
        d, nx, ny, cx, cy, _, hidden, _ = point_polygon_feature(
            ox, oy, world, n, margin + r, part_surface, part_corners
        )
        d -= r
        if d < margin and hidden:
            g, gnx, gny, e = surface_in_front(ox, oy, world, n, margin + r, part_surface)
            if e >= 0:
                d, nx, ny, hidden = g - r, gnx, gny, False
                cx, cy = ox - g * gnx, oy - g * gny
        if d < margin and not hidden:
            nc = _add(contacts, nc, d, -nx, -ny, cx, cy)
        else:
            clear = min(clear, d)
    return nc, clear


@leaf_kernel
def plain_part(
    bcounts: np.ndarray, bsurface: np.ndarray, bcorners: np.ndarray, bdiscs: np.ndarray
) -> bool:
    """Whether a part (:class:`validity.scene_arrays.PartArrays`) is one convex polygon with
    every edge a surface and every vertex a corner, and no disc: the peg. The steppers ask
    such a part with :func:`find_contacts` on its polygon, as before parts had pieces (the
    views of :func:`find_part_contacts` cost a fifth of a step)."""
    if bcounts.shape[0] != 1 or bdiscs.shape[0] != 0:
        return False
    for k in range(bcounts[0]):
        if not (bsurface[0, k] and bcorners[0, k]):
            return False
    return True


@leaf_kernel
def _disc_contacts(
    k: int,
    wdiscs: np.ndarray,
    world: np.ndarray,
    wcounts: np.ndarray,
    wboxes: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    surface: np.ndarray,
    corners: np.ndarray,
    margin: float,
    contacts: np.ndarray,
    nc: int,
) -> tuple[int, float]:
    """Contacts of the part's disc k (placed: ``wdiscs (D, 3)``) with the obstacles, as
    :func:`find_contacts`'s for a polygon piece: a disc touches a polygon where its centre's
    nearest surface feature is (a centre inside the solid: its depth in the whole solid,
    :func:`solid_depth`), and a disc along the line of centres. The contact point is the
    disc's point nearest the obstacle; one that lies inside a polygon piece of the part
    (``world``, ``wcounts``, their boxes ``wboxes``) is on no surface of the part and is
    dropped."""
    cx, cy, r = wdiscs[k, 0], wdiscs[k, 1], wdiscs[k, 2]
    clear = np.inf
    if _strictly_inside(verts, counts, aabbs, cx, cy):
        depth, nx, ny = solid_depth(cx, cy, verts, counts, aabbs, surface, circles)
        if depth < np.inf:
            nc = _add(contacts, nc, -depth - r, nx, ny, cx - r * nx, cy - r * ny)
    else:
        for p in range(verts.shape[0]):
            box = aabbs[p]
            gap = math.hypot(max(box[0] - cx, 0.0, cx - box[2]), max(box[1] - cy, 0.0, cy - box[3]))
            if gap - r >= margin:
                clear = min(clear, gap - r)
                continue
            d, nx, ny, _, _, _, hidden, _ = point_polygon_feature(
                cx, cy, verts[p], counts[p], margin + r, surface[p], corners[p]
            )
            d -= r
            if d < margin and hidden:
                g, gnx, gny, e = surface_in_front(
                    cx, cy, verts[p], counts[p], margin + r, surface[p]
                )
                if e >= 0:
                    d, nx, ny, hidden = g - r, gnx, gny, False
            px, py = cx - r * nx, cy - r * ny
            if d < margin and not hidden and not _strictly_inside(world, wcounts, wboxes, px, py):
                nc = _add(contacts, nc, d, nx, ny, px, py)
            else:
                clear = min(clear, d)
    for q in range(circles.shape[0]):
        dx, dy = cx - circles[q, 0], cy - circles[q, 1]
        dist = math.hypot(dx, dy)
        d = dist - r - circles[q, 2]
        if d >= margin or dist <= _TINY:
            clear = min(clear, d)
            continue
        nx, ny = dx / dist, dy / dist
        px, py = cx - r * nx, cy - r * ny
        if _strictly_inside(world, wcounts, wboxes, px, py):
            clear = min(clear, d)
        else:
            nc = _add(contacts, nc, d, nx, ny, px, py)
    return nc, clear


@njit(cache=True)  # polygon_aabbs allocates
def find_part_contacts(
    world: np.ndarray,
    wcounts: np.ndarray,
    part_surface: np.ndarray,
    part_corners: np.ndarray,
    wdiscs: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    surface: np.ndarray,
    corners: np.ndarray,
    margin: float,
    contacts: np.ndarray,
) -> tuple[int, float]:
    """:func:`find_contacts` for a part of convex pieces ``world (Q, K, 2)`` (placed,
    ``wcounts (Q,)`` vertices each, padding repeating the last) with their surface and corner
    flags ``(Q, K)`` (:mod:`validity.solid_surface` applied to the part: seams between its
    pieces are no surface) and discs ``wdiscs (D, 3)`` (placed). Returns ``(count, clear)``
    over every piece: the contacts of each piece with the obstacles, none between pieces. A
    part that is one convex polygon (:func:`plain_part`, the peg) is better asked with
    :func:`find_contacts` on that polygon: no view of a piece per call, no flags to read."""
    nc = 0
    clear = np.inf
    for q in range(world.shape[0]):
        nc, c = find_contacts(
            world[q, : wcounts[q]],
            verts,
            counts,
            aabbs,
            circles,
            surface,
            corners,
            margin,
            contacts,
            nc,
            part_surface[q],
            part_corners[q],
        )
        clear = min(clear, c)
    if wdiscs.shape[0] == 0:
        return nc, clear
    wboxes = polygon_aabbs(world, wcounts)
    for k in range(wdiscs.shape[0]):
        nc, c = _disc_contacts(
            k,
            wdiscs,
            world,
            wcounts,
            wboxes,
            verts,
            counts,
            aabbs,
            circles,
            surface,
            corners,
            margin,
            contacts,
            nc,
        )
        clear = min(clear, c)
    return nc, clear
