"""The geometry kernel against shapely (GEOS), an independent reference, and analytic cases.

Reference for the yes/no penetration test: shapely's intersection area of the placed part
with the union of the polygon obstacles (> 0: penetration), and for each disc shapely's exact
distance from its centre to the part polygon (< radius: penetration; shapely's buffered discs
are polygons and would be off by ~1e-3). Reference for distances of separated shapes:
``shapely.distance``. Reference for penetration depths: hand-computed cases, confirmed by
moving the part by that depth and asking shapely whether the shapes still overlap.

Tolerance band: poses whose kernel signed distance is within ``BAND`` of zero (touching, to
rounding) may go either way; they are excluded from the comparison and counted.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pytest
import shapely
from shapely.geometry import Point, Polygon

from feeders.design import PRESETS
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.halton import halton_designs
from feeders.part import Peg
from feeders.scene import Goal, Scene
from feeders.shapes import Obstacles, convex_pieces
from validity.geometric import GeometricLevel
from validity.geometry_kernel import (
    clearance_at_pose,
    convex_signed_distance,
    penetrates,
    pose_vertices,
)
from validity.pose_samples import cross_check_poses
from validity.scene_arrays import SceneArrays

BAND = 1e-9  # |signed distance| below which a pose counts as touching and is not compared
DISTANCE_TOL = 1e-9  # kernel distance vs shapely distance, separated shapes (length units)
N_POSES = 20_000  # per scene
HALTON_SEED = 7
# The hand-worked cases below use this part: 2 x 1, centre of mass 0.25 toward the heavy end.
PART = Peg.two_density(length=2.0, width=1.0, heavy_fraction=0.75)
BODY = PART.body_vertices()


# --------------------------------------------------------------------------- scenes


def free_scene(name: str, polygons: list[np.ndarray], circles: np.ndarray) -> Scene:
    """A free-form scene (no feeder design) around the given obstacles."""
    obstacles = Obstacles(tuple(np.asarray(p, dtype=float) for p in polygons), circles)
    return Scene(
        name=name,
        obstacles=obstacles,
        part=PART,
        bounds=(-6.0, 6.0, -6.0, 6.0),
        starts={"heavy_leading": (0.0, 0.0, 0.0)},
        goal=Goal(x_min=-1.0, x_max=1.0, y_min=-1.0, y_max=1.0, yaw=0.0, yaw_tol=0.5),
    )


def _hexagon(cx: float, cy: float, r: float) -> np.ndarray:
    angles = np.arange(6) * math.pi / 3
    return np.column_stack([cx + r * np.cos(angles), cy + r * np.sin(angles)])


L_SHAPE = np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]])


def _free_form() -> Scene:
    """Triangle, quad, rotated square, hexagon and an L (as triangles), two discs; quads and
    the hexagon pad the triangles to 6 vertices in the packed arrays."""
    polygons = [
        np.array([[-5.0, -5.0], [-3.0, -4.5], [-4.2, -2.5]]),
        np.array([[1.0, -5.0], [4.5, -4.6], [4.0, -3.2], [1.2, -3.5]]),
        np.array([[-4.0, 2.5], [-2.8, 3.7], [-4.0, 4.9], [-5.2, 3.7]]),
        _hexagon(3.5, 3.5, 1.2),
        *[piece + np.array([-1.0, -1.5]) for piece in convex_pieces(L_SHAPE)],
    ]
    circles = np.array([[-3.5, -0.5, 0.7], [3.8, 0.2, 0.4]])
    return free_scene("free-form", polygons, circles)


def _halton_scenes(count: int = 3) -> list[Scene]:
    """The first ``count`` Halton designs (seed ``HALTON_SEED``) that build."""
    scenes = []
    for i, design in enumerate(halton_designs(4 * count, seed=HALTON_SEED)):
        try:
            scenes.append(build_feeder(design, PART, name=f"halton seed {HALTON_SEED} #{i}"))
        except DegenerateDesign:
            continue
        if len(scenes) == count:
            break
    assert len(scenes) == count, f"only {len(scenes)} Halton designs of seed {HALTON_SEED} build"
    return scenes


SCENE_NAMES = ["table3", "halton-1", "halton-2", "halton-3", "free-form"]
# The Halton designs (~4 s each) in CI's longer job; table3 and free-form by default.
SCENE_CASES = [
    pytest.param(n, marks=pytest.mark.slow) if n.startswith("halton") else n for n in SCENE_NAMES
]


@functools.cache
def _scene(name: str) -> Scene:
    """The scene called ``name`` in SCENE_NAMES (halton-k: the k-th Halton design that builds)."""
    if name == "table3":
        return build_feeder(PRESETS["table3"], PART, name="table3")
    if name == "free-form":
        return _free_form()
    return _halton_scenes()[int(name.split("-")[1]) - 1]


# --------------------------------------------------------------------------- references


def part_polygons(poses: np.ndarray) -> np.ndarray:
    """Shapely polygons of the part at each pose (rotation written out here, not the kernel's)."""
    x, y, yaw = poses[:, 0:1], poses[:, 1:2], poses[:, 2:3]
    c, s = np.cos(yaw), np.sin(yaw)
    wx = x + c * BODY[:, 0] - s * BODY[:, 1]
    wy = y + s * BODY[:, 0] + c * BODY[:, 1]
    return shapely.polygons(np.stack([wx, wy], axis=-1))


def shapely_reference(
    polygons: list[np.ndarray], circles: np.ndarray, poses: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """``(penetrating, distance)`` per pose from shapely; distance is meaningful when apart."""
    parts = part_polygons(poses)
    penetrating = np.zeros(len(poses), dtype=bool)
    distance = np.full(len(poses), np.inf)
    if polygons:
        solid = shapely.unary_union([Polygon(p) for p in polygons])
        shapely.prepare(solid)
        penetrating = shapely.area(shapely.intersection(parts, solid)) > 0.0
        distance = shapely.distance(parts, solid)
    for cx, cy, r in np.asarray(circles).reshape(-1, 3):
        to_centre = shapely.distance(Point(cx, cy), parts)  # 0 when the centre is inside
        penetrating |= to_centre < r
        distance = np.minimum(distance, to_centre - r)
    return penetrating, distance


def _kernel(arrays: SceneArrays, poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(clearance, penetrates)`` per pose from the kernel under test."""
    a = arrays
    world = np.empty_like(a.part.body[0])
    clearance = np.empty(len(poses))
    pen = np.empty(len(poses), dtype=bool)
    for k, (x, y, yaw) in enumerate(poses):
        clearance[k] = clearance_at_pose(
            a.part.body[0], x, y, yaw, a.verts, a.counts, a.aabbs, a.circles, -np.inf
        )
        pose_vertices(a.part.body[0], x, y, yaw, world)
        pen[k] = penetrates(world, a.verts, a.counts, a.aabbs, a.circles)
    return clearance, pen


@dataclass(frozen=True)
class CrossCheck:
    poses: np.ndarray
    clearance: np.ndarray
    penetrates: np.ndarray
    ref_penetrating: np.ndarray
    ref_distance: np.ndarray


def _cross_check(scene: Scene, poses: np.ndarray, polygons: list | None = None) -> CrossCheck:
    clearance, pen = _kernel(SceneArrays.from_scene(scene), poses)
    if polygons is None:
        polygons = list(scene.obstacles.polygons)
    ref_pen, ref_dist = shapely_reference(polygons, scene.obstacles.circles, poses)
    return CrossCheck(poses, clearance, pen, ref_pen, ref_dist)


@functools.cache
def _scene_check(name: str) -> CrossCheck:
    scene = _scene(name)
    seed = 1000 + SCENE_NAMES.index(name)
    return _cross_check(scene, cross_check_poses(scene, N_POSES, seed))


def _assert_verdicts_agree(check: CrossCheck, label: str, min_fraction: float = 0.1) -> None:
    in_band = np.abs(check.clearance) < BAND
    outside = ~in_band
    n_out = int(outside.sum())
    n_pen = int((check.ref_penetrating & outside).sum())
    counts = (
        f"{label}: {len(check.poses)} poses, {int(in_band.sum())} in the band "
        f"|d| < {BAND:g} (excluded), {n_out} compared: {n_pen} penetrating, "
        f"{n_out - n_pen} clear (shapely)"
    )
    assert min(n_pen, n_out - n_pen) >= min_fraction * n_out, f"unbalanced sample; {counts}"
    by_clearance = outside & ((check.clearance < 0.0) != check.ref_penetrating)
    by_penetrates = outside & (check.penetrates != check.ref_penetrating)
    worst = check.clearance[by_clearance | by_penetrates]
    assert not by_clearance.any() and not by_penetrates.any(), (
        f"{counts}; disagreements with shapely: clearance < 0 {int(by_clearance.sum())}, "
        f"penetrates {int(by_penetrates.sum())}; kernel distances there: {worst[:5]}"
    )


def _assert_distances_agree(check: CrossCheck, label: str) -> None:
    apart = ~check.ref_penetrating & (check.ref_distance > 0.0)
    error = np.abs(check.clearance[apart] - check.ref_distance[apart])
    assert apart.sum() > 0, f"{label}: no separated poses to compare"
    worst = int(np.argmax(error))
    assert error[worst] <= DISTANCE_TOL, (
        f"{label}: {int((error > DISTANCE_TOL).sum())} of {int(apart.sum())} separated poses "
        f"differ from shapely.distance by more than {DISTANCE_TOL:g}; worst {error[worst]:.3g} "
        f"at pose {check.poses[apart][worst]}"
    )


# --------------------------------------------------------------------------- random poses


@pytest.mark.parametrize("name", SCENE_CASES)
def test_penetration_verdict_matches_shapely(name: str) -> None:
    """clearance < 0 and ``penetrates`` both equal shapely's verdict (intersection area > 0,
    or a disc centre nearer the part than its radius) on 20,000 seeded poses outside the band."""
    _assert_verdicts_agree(_scene_check(name), name)


@pytest.mark.parametrize("name", SCENE_CASES)
def test_distance_matches_shapely_when_apart(name: str) -> None:
    """For separated shapes the kernel's clearance equals shapely.distance (to the polygon
    union, and centre distance minus radius for discs) within 1e-9."""
    _assert_distances_agree(_scene_check(name), name)


# --------------------------------------------------------------------------- analytic depths

FLOOR = np.array([[-10.0, -5.0], [10.0, -5.0], [10.0, 0.0], [-10.0, 0.0]])  # top face y = 0


def _clearance(polygons: list[np.ndarray], circles: np.ndarray, pose: tuple) -> float:
    arrays = SceneArrays.from_scene(free_scene("case", polygons, circles))
    a = arrays
    return float(
        clearance_at_pose(a.part.body[0], *pose, a.verts, a.counts, a.aabbs, a.circles, -np.inf)
    )


def _shapely_overlaps(polygons: list[np.ndarray], circles: np.ndarray, pose: tuple) -> bool:
    return bool(shapely_reference(polygons, circles, np.array([pose]))[0][0])


def _moved(pose: tuple, direction: tuple, by: float) -> tuple:
    return (pose[0] + by * direction[0], pose[1] + by * direction[1], pose[2])


NO_DISCS = np.zeros((0, 3))


@pytest.mark.parametrize("depth", [1e-3, 0.123, 0.4, 0.9])
def test_box_into_wide_box_depth(depth: float) -> None:
    """Part at yaw 0 (y extent +-0.5 about the centre of mass) sunk ``depth`` into a floor
    20 wide: pushing it up by ``depth`` is the smallest separating move (sideways needs > 2),
    so the clearance is -depth. Shapely: overlap just below that move, none just above."""
    pose = (0.3, 0.5 - depth, 0.0)
    assert _clearance([FLOOR], NO_DISCS, pose) == pytest.approx(-depth, abs=1e-12)
    assert _shapely_overlaps([FLOOR], NO_DISCS, _moved(pose, (0, 1), depth - 1e-7))
    assert not _shapely_overlaps([FLOOR], NO_DISCS, _moved(pose, (0, 1), depth + 1e-7))


@pytest.mark.parametrize("gap", [1e-6, 0.05, 0.7])
def test_box_above_wide_box_distance(gap: float) -> None:
    """The same part ``gap`` above the floor: the clearance is the gap."""
    assert _clearance([FLOOR], NO_DISCS, (0.3, 0.5 + gap, 0.0)) == pytest.approx(gap, abs=1e-12)


@pytest.mark.parametrize(("radius", "depth"), [(0.3, 0.01), (0.3, 0.25), (0.1, 0.15)])
def test_disc_into_edge_depth(radius: float, depth: float) -> None:
    """Part at the origin, yaw 0: its top edge is y = 0.5 for x in [-1.25, 0.75]. A disc above
    the middle of that edge with centre y = 0.5 + radius - depth overlaps it by ``depth`` (the
    centre inside the part when depth > radius, nearest edge still the top one), so the
    clearance is -depth; moving the disc up by depth separates them (shapely)."""
    disc = np.array([[-0.25, 0.5 + radius - depth, radius]])
    pose = (0.0, 0.0, 0.0)
    assert _clearance([], disc, pose) == pytest.approx(-depth, abs=1e-12)
    assert _shapely_overlaps([], disc, _moved(pose, (0, -1), depth - 1e-7))
    assert not _shapely_overlaps([], disc, _moved(pose, (0, -1), depth + 1e-7))


@pytest.mark.parametrize("depth", [0.01, 0.2, 0.6])
def test_rotated_part_on_obstacle_corner_depth(depth: float) -> None:
    """Obstacle: the quadrant x >= 0, y <= 0 (a 10 x 10 box), its corner at the origin.
    Part at yaw pi/4: its bottom face (body y = -0.5) has outward normal n = (1, -1)/sqrt2 and
    body midpoint (-0.25, -0.5), at world offset m = (0.25/sqrt2, -0.75/sqrt2). With the
    centre of mass at depth * n - m the corner is ``depth`` inside that face, at its middle.

    Minimum translation by hand (separating-axis overlaps): along n, depth; along the face
    direction (1, 1)/sqrt2, 8.07; along x and y (obstacle faces), 1/sqrt2 + depth/sqrt2. So the
    clearance is -depth, achieved along the diagonal -n, not along an obstacle face normal."""
    box = np.array([[0.0, -10.0], [10.0, -10.0], [10.0, 0.0], [0.0, 0.0]])
    r2 = math.sqrt(2.0)
    n = (1.0 / r2, -1.0 / r2)
    m = (0.25 / r2, -0.75 / r2)
    pose = (depth * n[0] - m[0], depth * n[1] - m[1], math.pi / 4)
    assert _clearance([box], NO_DISCS, pose) == pytest.approx(-depth, abs=1e-12)
    away = (-n[0], -n[1])
    assert _shapely_overlaps([box], NO_DISCS, _moved(pose, away, depth - 1e-7))
    assert not _shapely_overlaps([box], NO_DISCS, _moved(pose, away, depth + 1e-7))
    # moving along an obstacle face normal by depth is not enough: the diagonal is shorter
    assert _shapely_overlaps([box], NO_DISCS, _moved(pose, (-1, 0), depth + 1e-7))
    assert _shapely_overlaps([box], NO_DISCS, _moved(pose, (0, 1), depth + 1e-7))


@pytest.mark.parametrize("theta", [0.3, -1.1, 2.5])
def test_tilted_part_corner_into_floor_depth(theta: float) -> None:
    """Part at yaw theta above the floor y <= 0: a corner (bx, by) sits at height
    y + sin(theta) bx + cos(theta) by, so with y = depth_0 - min over corners, the lowest
    corner is ``depth`` below the floor (depth_0 = -depth): clearance -depth (the floor is
    20 wide, so no tilted axis gives a smaller overlap)."""
    depth = 0.07
    lowest = min(math.sin(theta) * bx + math.cos(theta) * by for bx, by in BODY)
    pose = (0.1, -depth - lowest, theta)
    assert _clearance([FLOOR], NO_DISCS, pose) == pytest.approx(-depth, abs=1e-12)
    assert _shapely_overlaps([FLOOR], NO_DISCS, _moved(pose, (0, 1), depth - 1e-7))
    assert not _shapely_overlaps([FLOOR], NO_DISCS, _moved(pose, (0, 1), depth + 1e-7))


# --------------------------------------------------------------------------- edge cases


@pytest.mark.parametrize(
    ("polygons", "circles", "pose"),
    [
        ([FLOOR], NO_DISCS, (0.0, 0.5, 0.0)),  # bottom face on the floor's top face
        ([np.array([[0.75, 0.5], [2.0, 0.5], [2.0, 2.0], [0.75, 2.0]])], NO_DISCS, (0.0, 0.0, 0.0)),
        ([], np.array([[-0.25, 0.75, 0.25]]), (0.0, 0.0, 0.0)),  # disc on the top face
        ([], np.array([[1.0, 0.5, 0.25]]), (0.0, 0.0, 0.0)),  # disc on a corner (0.75, 0.5)
    ],
    ids=["face-on-face", "corner-on-corner", "disc-on-face", "disc-on-corner"],
)
def test_touching_exactly_is_not_penetrating(
    polygons: list[np.ndarray], circles: np.ndarray, pose: tuple
) -> None:
    """Exact contact (all coordinates binary-exact): distance 0, so valid (psi_n >= 0).
    Shapely agrees it is contact: distance 0 and zero intersection area."""
    scene = free_scene("touch", polygons, circles)
    a = SceneArrays.from_scene(scene)
    world = np.empty_like(a.part.body[0])
    pose_vertices(a.part.body[0], *pose, world)
    d = clearance_at_pose(a.part.body[0], *pose, a.verts, a.counts, a.aabbs, a.circles, -np.inf)
    ref_pen, ref_dist = shapely_reference(polygons, circles, np.array([pose]))
    assert ref_dist[0] == 0.0 and not ref_pen[0], "the reference says this is not contact"
    assert d == 0.0
    assert not penetrates(world, a.verts, a.counts, a.aabbs, a.circles)
    assert GeometricLevel(scene).is_valid(pose)


def test_padded_triangle_matches_shapely() -> None:
    """A triangle packed next to a hexagon is padded to 6 vertices by repeating its last one.
    Near the triangle, the kernel's verdicts and distances equal shapely's; and
    convex_signed_distance gives the same value whether it is told the true count (3) or the
    padded count (6: the repeated vertices make zero-length edges, which must be harmless)."""
    triangle = np.array([[-1.0, -1.0], [1.5, -0.5], [0.0, 1.2]])
    hexagon = _hexagon(8.0, 8.0, 1.0)
    scene = free_scene("padded", [triangle, hexagon], NO_DISCS)
    verts, counts, _ = scene.obstacles.packed()
    assert counts.tolist() == [3, 6]
    assert np.all(verts[0, 3:] == triangle[-1]), "the triangle is not padded as assumed"
    near = free_scene("triangle", [triangle], NO_DISCS)
    check = _cross_check(scene, cross_check_poses(near, 4000, 21, near_fraction=0.8))
    _assert_verdicts_agree(check, "padded triangle")
    _assert_distances_agree(check, "padded triangle")
    world = np.empty_like(BODY)
    for x, y, yaw in check.poses[:500]:
        pose_vertices(BODY, x, y, yaw, world)
        true_count = convex_signed_distance(world, 4, verts[0], 3)
        padded = convex_signed_distance(world, 4, verts[0], 6)
        assert padded == pytest.approx(true_count, abs=1e-15)


def test_l_shape_pieces_match_shapely_l() -> None:
    """An L-shaped (non-convex) obstacle split by convex_pieces into triangles: the kernel on
    the pieces agrees with shapely on the original L polygon (verdicts outside the band, and
    distances when apart), including poses that straddle the cut edges between pieces."""
    pieces = convex_pieces(L_SHAPE)
    assert len(pieces) >= 2 and all(len(p) == 3 for p in pieces)
    assert shapely.unary_union([Polygon(p) for p in pieces]).symmetric_difference(
        Polygon(L_SHAPE)
    ).area == pytest.approx(0.0, abs=1e-12)
    scene = free_scene("L", pieces, NO_DISCS)
    outline = free_scene("L outline", [L_SHAPE], NO_DISCS)  # poses against the L's own edges
    poses = np.vstack(
        [
            cross_check_poses(outline, 3000, 31, near_fraction=0.8),
            cross_check_poses(scene, 3000, 32, near_fraction=0.8),
        ]
    )
    check = _cross_check(scene, poses, polygons=[L_SHAPE])
    _assert_verdicts_agree(check, "L shape")
    _assert_distances_agree(check, "L shape")


# --------------------------------------------------------------------------- several obstacles

TOUCHED_THEN_HIT = [
    FLOOR,  # touched exactly by the part at (0, 0.5, 0): distance 0
    np.array([[0.0, 0.2], [0.3, 0.2], [0.3, 0.6], [0.0, 0.6]]),  # inside the part: depth 0.3
]


def test_penetrates_sees_obstacle_after_a_touching_one() -> None:
    """Part touching the floor exactly and overlapping a small box listed after it: shapely
    finds overlap; ``penetrates`` (and so GeometricLevel.is_valid) must say so."""
    pose = (0.0, 0.5, 0.0)
    assert _shapely_overlaps(TOUCHED_THEN_HIT, NO_DISCS, pose)
    scene = free_scene("touch+hit", TOUCHED_THEN_HIT, NO_DISCS)
    a = SceneArrays.from_scene(scene)
    world = np.empty_like(a.part.body[0])
    pose_vertices(a.part.body[0], *pose, world)
    assert penetrates(world, a.verts, a.counts, a.aabbs, a.circles)
    assert not GeometricLevel(scene).is_valid(pose)


def test_clearance_sees_obstacle_after_a_touching_one() -> None:
    """Same pose as above: the part spans x in [-1.25, 0.75], y in [0, 1]; the small box
    [0, 0.3] x [0.2, 0.6] lies inside it. Separating moves (worked by hand): up 0.6, down 0.8,
    left 0.75, right 1.55, so the signed distance is -0.6, not the floor's 0."""
    clearance = _clearance(TOUCHED_THEN_HIT, NO_DISCS, (0.0, 0.5, 0.0))
    assert clearance == pytest.approx(-0.6, abs=1e-12)


def test_clearance_is_the_deepest_of_two_penetrations() -> None:
    """Part at (0, 0.4, 0): 0.1 into the floor and 0.3 into a box rising to y = 0.2 under
    its bottom face (the box's sideways overlaps are >= 1.05): the minimum is -0.3."""
    deeper = np.array([[-0.3, -1.0], [0.3, -1.0], [0.3, 0.2], [-0.3, 0.2]])
    assert _clearance([FLOOR], NO_DISCS, (0.0, 0.4, 0.0)) == pytest.approx(-0.1, abs=1e-12)
    assert _clearance([deeper], NO_DISCS, (0.0, 0.4, 0.0)) == pytest.approx(-0.3, abs=1e-12)
    assert _clearance([FLOOR, deeper], NO_DISCS, (0.0, 0.4, 0.0)) == pytest.approx(-0.3, abs=1e-12)
