"""The geometric level (paper Eq. 9, Algorithm 1) as a specification.

References: the closed form ``q + T u`` for free motion; the documented stepping (``n =
ceil(T / h)`` steps of ``dt = T / n``) for where a blocked propagation must stop; shapely
(via :func:`test_geometry_kernel.shapely_reference`) for whether the part overlaps an
obstacle at, and between, the poses the level visits.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Sequence

import numpy as np
import pytest
import shapely
from test_geometry_kernel import PART, free_scene, part_polygons, shapely_reference

from feeders.design import PRESETS
from feeders.feeder import build_feeder
from feeders.scene import InputSet, Scene
from validity.geometric import DEFAULT_STEP, GeometricLevel, propagate_increments
from validity.geometry_kernel import penetrates, pose_vertices
from validity.pose_samples import cross_check_poses

NO_DISCS = np.zeros((0, 3))
AREA_TOL = 1e-12  # shapely intersection area counted as contact, not overlap (length^2)
TURNING_AREA_TOL = 1e-4  # allowed chord-cutting overlap between checked poses while turning


@functools.cache
def _table3() -> Scene:
    return build_feeder(PRESETS["table3"], PART, name="table3")


def _increments(
    level: GeometricLevel, q: Sequence[float], u: Sequence[float], duration: float
) -> tuple:
    """The level's stepping, with its step count and blocked flag: (x, y, yaw, steps, blocked)."""
    a = level.arrays
    return propagate_increments(*q, *u, duration, level.step, *a.pose_scene)


def _within(bounds: tuple, x: float, y: float) -> bool:
    return bounds[0] <= x <= bounds[1] and bounds[2] <= y <= bounds[3]


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def _random_controls(scene: Scene, n: int, rng: np.random.Generator) -> np.ndarray:
    """Controls uniform in U; a third of them at a corner of U (top speed and turn rate)."""
    low, high = scene.inputs.bounds()
    u = rng.uniform(low, high, (n, 3))
    corner = rng.uniform(size=n) < 1 / 3
    u[corner] = np.where(rng.uniform(size=(int(corner.sum()), 3)) < 0.5, low, high)
    return u


def _valid_poses(level: GeometricLevel, n: int, seed: int) -> np.ndarray:
    """``n`` seeded poses the level calls valid (from the cross-check sampler); in a feeder,
    only those with the centre of mass inside its interior (not outside its walls)."""
    poses = cross_check_poses(level.scene, 100 * n, seed)
    keep = np.array([level.is_valid(p) for p in poses])
    if level.scene.outline is not None:
        keep &= shapely.contains_xy(shapely.Polygon(level.scene.outline), poses[:, 0], poses[:, 1])
    assert keep.sum() >= n, f"only {int(keep.sum())} valid poses among {100 * n}"
    return poses[keep][:n]


def _overlap_area(scene: Scene, poses: np.ndarray) -> np.ndarray:
    """Shapely intersection area of the part at each pose with the polygon obstacles (discs
    via the exact centre distance: area is replaced by +inf when a disc overlaps)."""
    polygons = list(scene.obstacles.polygons)
    solid = shapely.unary_union([shapely.Polygon(p) for p in polygons])
    area = shapely.area(shapely.intersection(part_polygons(poses), solid))
    disc_hit, _ = shapely_reference([], scene.obstacles.circles, poses)
    return np.where(disc_hit, np.inf, area)


# --------------------------------------------------------------------------- free motion


def test_free_motion_is_closed_form_in_empty_scene() -> None:
    """No obstacles and bounds far away: propagate(q, u, T) is q + T u (yaw wrapped into
    [-pi, pi)) for random q, u in U and durations that are not multiples of h."""
    scene = free_scene("empty", [], NO_DISCS)
    scene = dataclasses.replace(scene, bounds=(-100.0, 100.0, -100.0, 100.0))
    level = GeometricLevel(scene)
    rng = np.random.default_rng(11)
    controls = _random_controls(scene, 300, rng)
    for u in controls:
        q = (rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-math.pi, math.pi))
        t = rng.uniform(0.001, 5.0)
        x, y, yaw = level.propagate(q, u, t)
        assert x == pytest.approx(q[0] + t * u[0], abs=1e-12)
        assert y == pytest.approx(q[1] + t * u[1], abs=1e-12)
        assert abs(_wrap(yaw - (q[2] + t * u[2]))) <= 1e-12


def test_free_motion_is_closed_form_in_table3() -> None:
    """In table3, from poses whose clearance exceeds the farthest any point of the part can
    move in T (T (sqrt2 max_speed + max_turn * bounding radius), plus 1e-6), and whose
    straight path stays in the bounds (both ends inside the box), the result is q + T u
    exactly as in free space."""
    scene = _table3()
    level = GeometricLevel(scene)
    rng = np.random.default_rng(12)
    reach_rate = math.sqrt(2) * scene.inputs.max_speed
    reach_rate += scene.inputs.max_turn * scene.part.bounding_radius()
    checked = 0
    for q, u in zip(_valid_poses(level, 400, 13), _random_controls(scene, 400, rng), strict=True):
        t = rng.uniform(0.001, 0.04)
        end = (q[0] + t * u[0], q[1] + t * u[1])
        if level.clearance(q) <= t * reach_rate + 1e-6 or not _within(scene.bounds, *end):
            continue
        x, y, yaw = level.propagate(q, u, t)
        assert (x, y) == pytest.approx(end, abs=1e-12)
        assert abs(_wrap(yaw - (q[2] + t * u[2]))) <= 1e-12
        checked += 1
    assert checked >= 50, f"only {checked} poses had enough clearance"


# --------------------------------------------------------------------------- blocked motion


def test_blocked_propagation_stops_at_last_valid_pose() -> None:
    """When a step would be invalid, propagation stops at a valid pose from which one more
    step dt = T / ceil(T / h) (= h here: T is a multiple of h) along u is invalid. Invalid
    next poses inside the bounds must penetrate: the kernel's ``penetrates`` says so and
    shapely finds positive overlap there, and none at the pose returned. (Valid poses outside
    the feeder's walls exist, and those may stop at the bounds instead: the next centre of
    mass must then be outside them; the start poses here are inside the feeder.)"""
    scene = _table3()
    level = GeometricLevel(scene)
    a = level.arrays
    rng = np.random.default_rng(21)
    duration = 3.0
    n = math.ceil(duration / level.step - 1e-9)
    dt = duration / n
    assert dt == pytest.approx(level.step, rel=1e-12)
    stops, nexts, at_bounds = [], [], 0
    for q, u in zip(_valid_poses(level, 200, 22), _random_controls(scene, 200, rng), strict=True):
        x, y, yaw, steps, blocked = _increments(level, q, u, duration)
        assert level.propagate(q, u, duration) == (x, y, yaw)
        if not blocked:
            continue
        assert steps < n
        assert level.is_valid((x, y, yaw))
        nxt = (x + dt * u[0], y + dt * u[1], _wrap(yaw + dt * u[2]))
        if not _within(scene.bounds, nxt[0], nxt[1]):
            at_bounds += 1
            continue
        world = np.empty_like(a.part.body[0])
        pose_vertices(a.part.body[0], *nxt, world)
        assert penetrates(world, a.verts, a.counts, a.aabbs, a.circles), f"{q=} {u=}"
        stops.append((x, y, yaw))
        nexts.append(nxt)
    assert len(stops) >= 100, f"only {len(stops)} of 200 propagations hit a wall ({at_bounds=})"
    stop_area = _overlap_area(scene, np.array(stops))
    next_area = _overlap_area(scene, np.array(nexts))
    assert np.all(stop_area <= AREA_TOL), f"max overlap at stops {stop_area.max():.3g}"
    assert np.all(next_area > 0.0), f"{int((next_area <= 0).sum())} next poses do not overlap"


def _thinnest_obstacle(scene: Scene) -> tuple[float, np.ndarray]:
    """(width, centre) of the thinnest obstacle: for a convex polygon the smallest extent over
    its edge normals (exact, rotating calipers), for a disc its diameter."""
    best = (math.inf, np.zeros(2))
    for p in scene.obstacles.polygons:
        e = np.roll(p, -1, axis=0) - p
        normals = np.column_stack([e[:, 1], -e[:, 0]]) / np.hypot(e[:, 0], e[:, 1])[:, None]
        proj = p @ normals.T
        width = float(np.min(proj.max(axis=0) - proj.min(axis=0)))
        if width < best[0]:
            best = (width, p.mean(axis=0))
    for cx, cy, r in scene.obstacles.circles:
        if 2 * r < best[0]:
            best = (2 * r, np.array([cx, cy]))
    return best


Shot = tuple[tuple[float, float, float], tuple[float, float, float]]  # (pose, control)


def _shots_at(
    scene: Scene, level: GeometricLevel, centre: np.ndarray, n: int, seed: int
) -> list[Shot]:
    """Valid poses within 2.5 of ``centre``, each with the top-speed controls (components
    +-max_speed or 0, at least one non-zero) that head toward it."""
    rng = np.random.default_rng(seed)
    m = scene.inputs.max_speed
    shots: list[Shot] = []
    while len(shots) < n:
        x, y = centre + rng.uniform(-2.5, 2.5, 2)
        q = (float(x), float(y), float(rng.uniform(-math.pi, math.pi)))
        if not level.is_valid(q):
            continue
        for vx in (-m, 0.0, m):
            for vy in (-m, 0.0, m):
                if (vx, vy) != (0.0, 0.0) and vx * (centre[0] - q[0]) + vy * (centre[1] - q[1]) > 0:
                    shots.append((q, (vx, vy, 0.0)))
    return shots


def _tunnelled_steps(
    scene: Scene, level: GeometricLevel, shots: list[Shot], duration: float
) -> int:
    """Replay each translation (closed form: pose k is q + k dt u) and count the steps whose
    swept region, the convex hull of the part at both ends (exact for a translation), overlaps
    an obstacle by more than AREA_TOL according to shapely."""
    polygons = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    polygons += [shapely.Point(cx, cy).buffer(r, 64) for cx, cy, r in scene.obstacles.circles]
    solid = shapely.unary_union(polygons)
    n = math.ceil(duration / level.step - 1e-9)
    dt = duration / n
    hulls = []
    for q, u in shots:
        *_, steps, _ = _increments(level, q, u, duration)
        k = np.arange(steps + 1)[:, None]
        poses = np.column_stack(
            [q[0] + k * dt * u[0], q[1] + k * dt * u[1], np.full(k.shape, q[2])]
        )
        corners = shapely.get_coordinates(part_polygons(poses)).reshape(len(poses), -1, 2)
        pairs = np.concatenate([corners[:-1], corners[1:]], axis=1)
        hulls.extend(shapely.convex_hull(shapely.multipoints(pairs)))
    area = shapely.area(shapely.intersection(np.array(hulls), solid))
    return int((area > AREA_TOL).sum())


def test_no_tunnelling_through_thinnest_obstacle_at_top_speed() -> None:
    """table3's thinnest obstacle (the protuberance, 2r = 0.202 thick) shot at from valid
    poses around it at the top speed of U (|vx|, |vy| = max_speed): every shot is stopped
    (by it or another wall) within 5 s, and no step's swept region overlaps any obstacle
    (shapely; discs as inscribed 256-gons, which can only under-report by < 1e-5 deep)."""
    scene = _table3()
    level = GeometricLevel(scene)
    width, centre = _thinnest_obstacle(scene)
    assert width == pytest.approx(2 * scene.design.r, rel=1e-12)
    shots = _shots_at(scene, level, centre, 60, seed=31)
    duration = 5.0
    blocked = sum(_increments(level, q, u, duration)[4] for q, u in shots)
    assert blocked == len(shots), f"{len(shots) - blocked} of {len(shots)} shots ran free"
    assert _tunnelled_steps(scene, level, shots, duration) == 0


def test_tunnelling_check_detects_long_steps() -> None:
    """The same check has teeth: with 300 times the top speed a step is 3 * sqrt2 = 4.2 long,
    more than the part's length plus the protuberance, and some shots step over an obstacle."""
    scene = dataclasses.replace(_table3(), inputs=InputSet(max_speed=300.0))
    level = GeometricLevel(scene)
    _, centre = _thinnest_obstacle(scene)
    shots = _shots_at(scene, level, centre, 60, seed=31)
    assert _tunnelled_steps(scene, level, shots, 5.0) > 0


def test_no_tunnelling_while_turning_at_top_rate() -> None:
    """Shots at the thinnest obstacle at top speed and top turn rate: 10 sub-poses between
    consecutive poses along the (closed-form) path overlap no obstacle by more than
    ``TURNING_AREA_TOL`` (shapely). Between two checked poses a turning corner may cut the
    chord of its arc, at most R (omega h)^2 / 8 = 1.6e-5 deep for R = 1.27 (the part's
    bounding radius): an overlap of area < 1.6e-5 * 2 (the part's length), far below the
    ~0.03 of passing into the 0.2-thick protuberance."""
    scene = _table3()
    level = GeometricLevel(scene)
    _, centre = _thinnest_obstacle(scene)
    rng = np.random.default_rng(41)
    duration = 5.0
    n = math.ceil(duration / level.step - 1e-9)
    dt = duration / n
    poses = []
    for q, (vx, vy, _) in _shots_at(scene, level, centre, 40, seed=42):
        u = (vx, vy, rng.choice((-1.0, 1.0)) * scene.inputs.max_turn)
        *_, steps, _ = _increments(level, q, u, duration)
        t = np.arange(10 * steps + 1) * dt / 10
        poses.append(np.column_stack([q[0] + t * u[0], q[1] + t * u[1], q[2] + t * u[2]]))
    area = _overlap_area(scene, np.vstack(poses))
    assert np.all(area <= TURNING_AREA_TOL), (
        f"{int((area > TURNING_AREA_TOL).sum())} of {len(area)} sub-poses overlap; "
        f"largest area {area.max():.3g}"
    )


# --------------------------------------------------------------------------- contract


def test_yaw_stays_in_half_open_range() -> None:
    """From yaws at and near +-pi, turning either way at up to the top rate, every result's
    yaw is in [-pi, pi)."""
    scene = free_scene("empty", [], NO_DISCS)
    level = GeometricLevel(scene)
    rng = np.random.default_rng(61)
    yaws = [-math.pi, math.nextafter(math.pi, 0.0), -math.pi + 1e-15, 3.0, -3.0, 0.0]
    for yaw in yaws:
        for omega in (-1.0, 1.0, *rng.uniform(-1.0, 1.0, 20)):
            for t in (DEFAULT_STEP, 0.5, 3.3, 7.0):
                _, _, out = level.propagate((0.0, 0.0, yaw), (0.0, 0.0, omega), t)
                assert -math.pi <= out < math.pi, f"{yaw=} {omega=} {t=} -> {out!r}"


def test_result_stays_within_bounds_of_empty_box() -> None:
    """In an empty 4 x 2 box, long propagations at up to top speed never leave scene.bounds
    (centre of mass), and every one that stops short of the closed form q + T u stops
    because the next step (dt along u) would leave the bounds."""
    scene = free_scene("empty", [], NO_DISCS)
    scene = dataclasses.replace(scene, bounds=(-2.0, 2.0, -1.0, 1.0))
    level = GeometricLevel(scene)
    rng = np.random.default_rng(71)
    starts = rng.uniform((-2, -1, -math.pi), (2, 1, math.pi), (200, 3))
    duration = 4.0
    dt = duration / math.ceil(duration / level.step - 1e-9)
    early = 0
    for q, u in zip(starts, _random_controls(scene, len(starts), rng), strict=True):
        x, y, _ = level.propagate(q, u, duration)
        assert _within(scene.bounds, x, y), f"{q=} {u=} -> {(x, y)}"
        if not _within(scene.bounds, q[0] + duration * u[0], q[1] + duration * u[1]):
            early += 1
            assert not _within(scene.bounds, x + dt * u[0], y + dt * u[1]), f"{q=} {u=}"
    assert early >= 100, f"only {early} of 200 propagations reached the bounds"


def test_result_stays_within_bounds_of_table3() -> None:
    """From valid table3 poses, propagations at up to top speed end within scene.bounds."""
    scene = _table3()
    level = GeometricLevel(scene)
    rng = np.random.default_rng(73)
    starts = _valid_poses(level, 200, 72)
    for q, u in zip(starts, _random_controls(scene, len(starts), rng), strict=True):
        x, y, _ = level.propagate(q, u, 4.0)
        assert _within(scene.bounds, x, y), f"{q=} {u=} -> {(x, y)}"


@pytest.mark.parametrize("step", [0.0, -0.01, 1.5, math.nan, math.inf])
def test_bad_step_is_refused(step: float) -> None:
    """h must be in (0, 1]: the error names the step and the allowed range."""
    with pytest.raises(ValueError, match=r"step.*\(0, 1\]"):
        GeometricLevel(_table3(), step=step)


def test_largest_step_is_accepted() -> None:
    """h = 1 is inside (0, 1] and is kept as given."""
    assert GeometricLevel(_table3(), step=1.0).step == 1.0


def test_inputs_set_bounds_the_controls() -> None:
    """control_bounds() is U of the scene's InputSet: +-max_speed, +-max_speed, +-max_turn."""
    scene = free_scene("empty", [], NO_DISCS)
    scene = dataclasses.replace(scene, inputs=InputSet(max_speed=2.5, max_turn=0.5))
    low, high = GeometricLevel(scene).control_bounds()
    assert low.tolist() == [-2.5, -2.5, -0.5] and high.tolist() == [2.5, 2.5, 0.5]
