"""Contact detection of the dynamic level, checked against shapely (an independent geometry
implementation) on poses of the part near the obstacles of table3 and of a free-form scene.

What is specified: every reported gap is the signed distance (shapely: distance outside,
minus the distance to the boundary inside) of the contact point to its obstacle; every
normal is a unit vector along which that distance grows at rate 1; every part corner within
the margin of an obstacle is reported; with no contact, ``clear`` is at least the margin and
never more than the true distance (shapely) to any obstacle.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import shapely
import shapely.affinity
from test_geometry_kernel import _scene

from validity.contact_kernel import (
    MAX_CONTACTS,
    find_contacts,
    point_polygon_feature,
)
from validity.geometry_kernel import polygon_aabbs, pose_vertices
from validity.scene_arrays import SceneArrays
from validity.solid_surface import split_at_cover

MARGIN = 0.05
N_POSES = 3000
TOL = 1e-9  # kernel vs shapely distances (length)
AXIS_TOL = 1e-6  # the same for a depth along an axis (shapely areas near 0 by bisection)
# The scenes of the shapely comparisons: each costs 12-15 s of shapely sampling once (_case);
# table3's in CI's longer job, free-form's by default.
SCENES = [pytest.param("table3", marks=pytest.mark.slow), "free-form"]


def _signed(geom, x: float, y: float) -> float:
    """Shapely's signed distance from (x, y) to a polygon or disc (negative inside)."""
    p = shapely.Point(x, y)
    d = geom.exterior.distance(p)
    return -d if geom.contains(p) else d


@functools.cache
def _case(name: str):
    scene = _scene(name)
    arrays = SceneArrays.from_scene(scene)
    polygons = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    rng = np.random.default_rng(11)
    x0, x1, y0, y1 = scene.bounds
    poses, worlds = [], []
    union = shapely.union_all(
        polygons + [shapely.Point(c[:2]).buffer(c[2], 256) for c in scene.obstacles.circles]
    )
    while len(poses) < N_POSES:
        pose = (rng.uniform(x0, x1), rng.uniform(y0, y1), rng.uniform(-math.pi, math.pi))
        world = np.empty_like(arrays.part.body[0])
        pose_vertices(arrays.part.body[0], *pose, world)
        gap = shapely.Polygon(world).distance(union)
        overlap = shapely.Polygon(world).intersection(union).area
        if gap < 2 * MARGIN and overlap < 0.02:  # near an obstacle, at most slightly in
            poses.append(pose)
            worlds.append(world)
    return scene, arrays, polygons, poses, worlds


def _contacts(arrays: SceneArrays, world: np.ndarray, margin: float = MARGIN):
    out = np.empty((MAX_CONTACTS, 5))
    nc, clear = find_contacts(
        world,
        arrays.verts,
        arrays.counts,
        arrays.aabbs,
        arrays.circles,
        arrays.surface,
        arrays.corners,
        margin,
        out,
    )
    return out[:nc], clear


@functools.cache
def _solid(name: str) -> tuple[shapely.Geometry, shapely.Geometry]:
    """The union of the obstacles of the scene ``name`` (discs as 1024-gons) and its
    boundary, made once per scene (it was made again for every contact: a third of the
    module's time). The union is taken on a 1e-12 grid: pieces meant to share an edge differ
    in the last bits of a coordinate (table3's funnel), and an exact union keeps a slit 1e-9
    wide between them as boundary."""
    scene = _scene(name)
    union = shapely.union_all(
        [shapely.Polygon(p) for p in scene.obstacles.polygons]
        + [shapely.Point(c[:2]).buffer(c[2], 256) for c in scene.obstacles.circles],
        grid_size=1e-12,
    )
    return union, union.boundary


def _solid_depth(scene, px: float, py: float) -> float | None:
    """shapely's distance from p to the boundary of the union of the obstacles when p is
    inside the union, else None."""
    union, boundary = _solid(scene.name)
    assert _scene(scene.name) is scene  # the union is of this very scene
    point = shapely.Point(px, py)
    return boundary.distance(point) if union.contains(point) else None


def _faces_ahead(scene, px: float, py: float, nx: float, ny: float) -> list[float]:
    """The distances from p to the lines of the polygons' faces with outward normal n that p
    is in front of and that are the solid's surface within the margin of p (shapely: a point
    of the face 1e-6 from its point nearest p lies on the union's boundary, with the union
    behind it and not in front): a corner whose nearest floor point lies under a ramp, or
    that lies inside another piece, is held by the floor's face beyond the ramp's foot
    (issue 35), at the distance to that face's line."""
    union, boundary = _solid(scene.name)
    out = []
    for poly in scene.obstacles.polygons:
        for a, b in zip(poly, np.roll(poly, -1, axis=0), strict=True):
            e = b - a
            length = math.hypot(*e)
            if length < 1e-12 or abs(e[1] / length - nx) + abs(-e[0] / length - ny) > 1e-9:
                continue
            line = nx * (px - a[0]) + ny * (py - a[1])
            t = min(1.0, max(0.0, float(np.dot((px, py) - a, e)) / length**2))
            if line < 0.0 or math.hypot(*((px, py) - (a + t * e))) >= MARGIN:
                continue
            for s in (t - 1e-6 / length, t + 1e-6 / length):
                q = a + min(1.0, max(0.0, s)) * e
                out_q = shapely.Point(q[0] + 1e-7 * nx, q[1] + 1e-7 * ny)
                in_q = shapely.Point(q[0] - 1e-7 * nx, q[1] - 1e-7 * ny)
                if (
                    boundary.distance(shapely.Point(q)) < 1e-9
                    and not union.contains(out_q)
                    and union.contains(in_q)
                ):
                    out.append(line)
                    break
    return out


def _reference_gap(scene, polygons, part, world, gap, nx, ny, px, py) -> tuple[str, float]:
    """The kind of contact that explains the row best, and shapely's signed distance for it:
    a part corner against a polygon, or in front of a surface face (:func:`_faces_ahead`); a
    polygon corner (at p - gap n) against the part; a disc
    (centre at p - (gap + r) n) against the part."""
    candidates = [("unexplained", math.inf)]
    if np.min(np.hypot(world[:, 0] - px, world[:, 1] - py)) < 1e-12:
        candidates += [("corner", _signed(g, px, py)) for g in polygons]
        # inside the solid, the depth is to the nearest point of the union's boundary
        depth = _solid_depth(scene, px, py)
        if depth is not None:
            candidates.append(("corner in the solid", -depth))
        candidates += [("surface face ahead", g) for g in _faces_ahead(scene, px, py, nx, ny)]
    ox, oy = px - gap * nx, py - gap * ny
    for poly in scene.obstacles.polygons:
        if np.min(np.hypot(poly[:, 0] - ox, poly[:, 1] - oy)) < 1e-9:
            candidates.append(("obstacle corner", _signed(part, ox, oy)))
    for cx, cy, r in scene.obstacles.circles:
        if math.hypot(px - (gap + r) * nx - cx, py - (gap + r) * ny - cy) < 1e-9:
            candidates.append(("disc", _signed(part, cx, cy) - r))
    if gap < 0.0:
        candidates += [("overlap along n", -_push_out(part, g, nx, ny)) for g in polygons]
    return min(candidates, key=lambda c: abs(c[1] - gap))


def _push_out(part, piece, nx: float, ny: float) -> float:
    """How far the part must move along (nx, ny) to overlap the piece by no area (shapely,
    bisection to 1e-12): the depth of a contact found by the separating-axis test, which a
    part straddling a thin piece has without any vertex inside the other shape."""

    def overlaps(t: float) -> bool:
        moved = shapely.affinity.translate(part, t * nx, t * ny)
        return moved.intersection(piece).area > 1e-20

    if not overlaps(0.0):
        return 0.0
    low, high = 0.0, 1.0
    while overlaps(high):
        high *= 2.0
    while high - low > 1e-12:
        mid = 0.5 * (low + high)
        low, high = (mid, high) if overlaps(mid) else (low, mid)
    return high


@pytest.mark.parametrize("name", SCENES)
def test_every_gap_is_shapelys_signed_distance_and_every_normal_its_gradient(name: str) -> None:
    """Each contact is explained by one kind with shapely's signed distance equal to its gap;
    for a part corner outside a polygon, stepping 1e-6 along the normal raises the distance by
    1e-6 (the normal is the distance's gradient, so the LCP's linearisation is first-order)."""
    scene, arrays, polygons, _, worlds = _case(name)
    kinds: dict[str, int] = {}
    for world in worlds:
        rows, _ = _contacts(arrays, world)
        part = shapely.Polygon(world)
        for gap, nx, ny, px, py in rows:
            assert math.hypot(nx, ny) == pytest.approx(1.0, abs=1e-12)
            kind, reference = _reference_gap(scene, polygons, part, world, gap, nx, ny, px, py)
            assert abs(reference - gap) < TOL, (kind, gap, reference)
            kinds[kind] = kinds.get(kind, 0) + 1
            if kind == "corner" and gap > 1e-6:
                own = min(polygons, key=lambda g: abs(_signed(g, px, py) - gap))
                ahead = _signed(own, px + 1e-6 * nx, py + 1e-6 * ny)
                assert ahead - gap == pytest.approx(1e-6, abs=1e-9)
    assert (
        kinds.get("corner", 0) + kinds.get("corner in the solid", 0) > 500
        and kinds.get("obstacle corner", 0) > 20
    )
    if len(scene.obstacles.circles):
        assert kinds.get("disc", 0) > 20


@pytest.mark.parametrize("name", SCENES)
def test_every_part_corner_within_the_margin_is_reported(name: str) -> None:
    """Completeness: a part corner whose shapely signed distance to the polygons is below the
    margin appears as a contact at that corner: with that gap when outside, with a gap <= 0
    when inside (the depth to the piece's own surface). Outside, corners nearer a disc than
    any polygon are the disc's (the disc's contact is at the part's point nearest its centre;
    a polygon edge inside a disc, such as the pin finger's end, is no surface), and a corner
    outside a polygon the part already overlaps may lie in the plane of the face that slides
    over that polygon's end (see the slab tests below), so only corners of parts apart from
    the polygon are checked outside."""
    scene, arrays, polygons, _, worlds = _case(name)
    missing = checked = 0
    for world in worlds:
        rows, _ = _contacts(arrays, world)
        part = shapely.Polygon(world)
        apart = [g for g in polygons if part.intersection(g).area == 0.0]
        for cx, cy in world:
            d = min(_signed(g, cx, cy) for g in polygons)
            if d >= 0.0 and apart:
                d = min(_signed(g, cx, cy) for g in apart)
            elif d >= 0.0:
                continue
            disc = min(
                (math.hypot(cx - ox, cy - oy) - r for ox, oy, r in scene.obstacles.circles),
                default=math.inf,
            )
            if d < MARGIN - 1e-9 and (d < 0.0 or d < disc - 1e-9):
                checked += 1
                hit = (np.abs(rows[:, 3] - cx) < 1e-12) & (np.abs(rows[:, 4] - cy) < 1e-12)
                hit &= (np.abs(rows[:, 0] - d) < TOL) if d >= 0 else (rows[:, 0] <= 0)
                missing += not hit.any()
    assert missing == 0
    assert checked > 1000


@pytest.mark.parametrize("name", SCENES)
def test_clear_is_a_true_lower_bound_when_nothing_is_in_reach(name: str) -> None:
    scene, arrays, polygons, _, worlds = _case(name)
    discs = [shapely.Point(c[:2]).buffer(c[2], 1024) for c in scene.obstacles.circles]
    free = 0
    for world in worlds:
        rows, clear = _contacts(arrays, world, margin=0.01)
        if len(rows):
            continue
        free += 1
        part = shapely.Polygon(world)
        true = min(part.distance(g) for g in polygons + discs)
        assert 0.01 <= clear <= true + 1e-6
    assert free > 50


def test_a_box_resting_on_a_floor_has_exactly_its_two_bottom_corners() -> None:
    """Hand-worked: a 2 x 1 box flat on y = 0 touches at (-1, 0) and (1, 0), normal +y; the
    floor's corners are far away and give nothing."""
    verts = np.array([[[-10.0, -1.0], [10.0, -1.0], [10.0, 0.0], [-10.0, 0.0]]])
    counts = np.array([4])
    world = np.array([[-1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 1.0]])
    out = np.empty((MAX_CONTACTS, 5))
    aabbs = polygon_aabbs(verts, counts)
    solid = split_at_cover(verts, counts, np.zeros((0, 3)))
    surface, corners = solid.surface, solid.corners
    nc, _ = find_contacts(
        world, verts, counts, aabbs, np.zeros((0, 3)), surface, corners, 0.01, out
    )
    assert nc == 2
    assert sorted(out[:2, 3]) == [-1.0, 1.0]
    np.testing.assert_allclose(out[:2, 0], 0.0, atol=1e-15)
    np.testing.assert_allclose(out[:2, 1:3], [[0.0, 1.0], [0.0, 1.0]], atol=1e-15)


def test_point_inside_a_square_gets_the_nearest_edge() -> None:
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    gap, nx, ny, cx, cy, vertex, _, _ = point_polygon_feature(0.9, 0.5, square, 4)
    assert (gap, nx, ny, cx, cy, vertex) == pytest.approx((-0.1, 1.0, 0.0, 1.0, 0.5, False))
    gap, nx, ny, cx, cy, vertex, _, _ = point_polygon_feature(2.0, 2.0, square, 4)
    assert gap == pytest.approx(math.sqrt(2)) and vertex
    assert (nx, ny) == pytest.approx((1 / math.sqrt(2), 1 / math.sqrt(2)))


def test_seams_between_pieces_of_one_solid_are_not_surfaces() -> None:
    """A floor cut into two squares: the shared edge is a seam, the others are surfaces; a
    corner touching the floor exactly at the seam's top end gets the floor normal (0, 1) from
    both pieces, never the seam's sideways normal (a ghost contact that would stop a slide)."""
    verts = np.array(
        [
            [[-2.0, -2.0], [0.0, -2.0], [0.0, 0.0], [-2.0, 0.0]],
            [[0.0, -2.0], [2.0, -2.0], [2.0, 0.0], [0.0, 0.0]],
        ]
    )
    counts = np.array([4, 4])
    solid = split_at_cover(verts, counts, np.zeros((0, 3)))
    surface = solid.surface
    assert surface.tolist() == [[True, False, True, True], [True, True, True, False]]
    world = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]) - np.array([0.0, 1e-12])
    out = np.empty((MAX_CONTACTS, 5))
    aabbs = polygon_aabbs(verts, counts)
    corners = solid.corners
    assert corners.tolist() == [[True, False, False, True], [False, True, True, False]]
    nc, _ = find_contacts(
        world, verts, counts, aabbs, np.zeros((0, 3)), surface, corners, 0.01, out
    )
    assert nc >= 2
    np.testing.assert_allclose(out[:nc, 1:3], np.tile([0.0, 1.0], (nc, 1)), atol=1e-9)


def _peg_on_slab(x_front: float, sunk: float) -> np.ndarray:
    """Corners of a 2.2 x 0.7 peg lying flat on the slab y <= 0, sunk ``sunk`` into it, its
    leading end face at x = ``x_front``."""
    return np.array([[-2.2, 0.0], [0.0, 0.0], [0.0, 0.7], [-2.2, 0.7]]) + np.array([x_front, -sunk])


def _slab_contacts(world: np.ndarray, verts: np.ndarray, margin: float = 0.02):
    counts = np.array([len(v) for v in verts])
    solid = split_at_cover(verts, counts, np.zeros((0, 3)))
    out = np.empty((MAX_CONTACTS, 5))
    nc, _ = find_contacts(
        world,
        solid.verts,
        solid.counts,
        polygon_aabbs(solid.verts, solid.counts),
        np.zeros((0, 3)),
        solid.surface,
        solid.corners,
        margin,
        out,
    )
    return out[:nc]


@pytest.mark.parametrize("sunk", [0.0, 1e-12, 1e-9, 1e-6, 2.7e-5, 1e-3])
@pytest.mark.parametrize("x_front", [-0.0087, -0.0018, 0.3])
def test_a_slab_end_under_a_sliding_face_is_no_contact_of_the_end_face(
    x_front: float, sunk: float
) -> None:
    """Issue 26, fault 1: a peg lying on a slab, its end face short of the slab's end vertex
    (0, 0) or past it. The vertex lies in the plane of the bottom face, within the overlap
    the pair already has: every contact pushes up (0, 1), none along the peg's axis (the
    phantom paired the vertex with the end face, gap 8.7 mm then 1.8 mm, and stopped the
    slide)."""
    slab = np.array([[[-20.0, -1.0], [0.0, -1.0], [0.0, 0.0], [-20.0, 0.0]]])
    rows = _slab_contacts(_peg_on_slab(x_front, sunk), slab)
    assert len(rows) >= 2
    np.testing.assert_allclose(rows[:, 1:3], np.tile([0.0, 1.0], (len(rows), 1)), atol=1e-9)


def test_a_wall_corner_in_front_of_the_end_face_is_a_contact_of_the_end_face() -> None:
    """The converse: a wall whose lower corner is 0.35 up the peg's end face, 4 mm ahead of
    it, is a contact of the end face (normal -x, gap 4e-3, at (0, 0.35)), as is the peg's
    upper corner against the wall's face, while the peg rests sunk 1e-6 in the floor."""
    pieces = np.array(
        [
            [[-20.0, -1.0], [20.0, -1.0], [20.0, 0.0], [-20.0, 0.0]],
            [[0.004, 0.35], [1.0, 0.35], [1.0, 3.0], [0.004, 3.0]],
        ]
    )
    rows = _slab_contacts(_peg_on_slab(0.0, 1e-6), pieces)
    wall = rows[np.abs(rows[:, 1] + 1.0) < 1e-12]
    assert len(wall) == 2
    np.testing.assert_allclose(wall[:, 0], 4e-3, atol=1e-12)
    points = wall[np.argsort(wall[:, 4]), 3:5]
    np.testing.assert_allclose(points, [[0.0, 0.35], [0.0, 0.7 - 1e-6]], atol=1e-12)


def test_a_part_straddling_a_thin_spike_gets_a_contact_as_deep_as_the_overlap() -> None:
    """Issue 26, fault 2: a thin spike through the middle of the peg, no vertex of either
    inside the other. The vertex tests see nothing; the separating-axis test gives a contact
    whose depth is what the peg must move along its normal to clear the spike (shapely)."""
    spike = np.array([[[-1.0, -3.0], [-0.9, -3.0], [-0.95, 3.0]]])
    world = _peg_on_slab(0.0, 0.0)
    rows = _slab_contacts(world, spike)
    assert len(rows) >= 1
    deepest = rows[np.argmin(rows[:, 0])]
    push = _push_out(shapely.Polygon(world), shapely.Polygon(spike[0]), deepest[1], deepest[2])
    assert deepest[0] == pytest.approx(-push, abs=AXIS_TOL)
    assert push > 0.09
