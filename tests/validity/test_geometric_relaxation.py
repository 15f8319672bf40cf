"""The geometric level as a relaxation of the verdict's drops (issue 21).

Reference: issue 21, "the geometric level as a relaxation": contact within a stated
tolerance is valid, the walls are judged with the feeder's manufacturing tolerance, planning
starts from the entry region; every pose of passive drops that work (nominal and perturbed)
is valid at the geometric level of the nominal design. Depths are checked against shapely:
the penetration depth of two convex polygons is the distance from the origin to the boundary
of their Minkowski difference (the convex hull of all vertex differences).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPoint, Point, Polygon

from experiments.drop.passive import passive_drop
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import entry_state, made_feeders
from feeders.design import PRESETS
from feeders.feeder import ORIENTATIONS, build_feeder
from validity import make_level
from validity.dynamic import DynamicLevel
from validity.geometric import GeometricLevel, pose_is_valid, propagate_increments
from validity.geometric_slack import relaxation_slack
from validity.geometry_kernel import clearance_at_pose, penetrates, pose_vertices
from validity.necessary import CONTACT_SLACK

TABLE3 = PRESETS["table3"]
# Designs that work (design_verdict: 40 of 40 from both entries, seed 0): table3, fig5a and
# two of table3's neighbours within its margins (docs/margins.md).
WORKING = {
    "table3": TABLE3,
    "fig5a": PRESETS["fig5a"],
    "table3-wide": dataclasses.replace(TABLE3, a=1.2, b=1.25, d=4.5, r=0.2, alpha=0.95),
    "table3-long": dataclasses.replace(TABLE3, a=1.15, b=1.2, c=0.76, d=4.0, r=0.25),
}


def _random_poses(scene, n: int, seed: int) -> np.ndarray:
    x0, x1, y0, y1 = scene.bounds
    rng = np.random.default_rng(seed)
    return np.column_stack(
        [rng.uniform(x0, x1, n), rng.uniform(y0, y1, n), rng.uniform(-math.pi, math.pi, n)]
    )


def test_zero_slack_is_the_old_check_on_random_poses():
    scene = build_feeder(TABLE3)
    level = GeometricLevel(scene)
    a = level.arrays
    world = np.empty_like(a.part.body[0])
    poses = _random_poses(scene, 4000, seed=3)
    invalid = 0
    for x, y, yaw in poses:
        pose_vertices(a.part.body[0], x, y, yaw, world)
        old = not penetrates(world, a.verts, a.counts, a.aabbs, a.circles)  # in bounds: drawn so
        assert level.is_valid((x, y, yaw)) is old
        zeros = (np.zeros(a.verts.shape[0]), np.zeros(a.circles.shape[0]))
        geometry = a.pose_scene
        assert pose_is_valid(x, y, yaw, *geometry) == old
        assert pose_is_valid(x, y, yaw, *geometry, *zeros) == old
        invalid += not old
    assert 0 < invalid < len(poses)  # both answers were asked for


def test_zero_slack_propagates_as_before():
    scene = build_feeder(TABLE3)
    a = GeometricLevel(scene).arrays
    zeros = (np.zeros(a.verts.shape[0]), np.zeros(a.circles.shape[0]))
    geometry = a.pose_scene
    start = scene.start("heavy_leading")
    rng = np.random.default_rng(5)
    blocked = 0
    for _ in range(200):
        u = rng.uniform(-1.0, 1.0, 3)
        old = propagate_increments(*start, *u, 3.0, 0.01, *geometry)
        new = propagate_increments(*start, *u, 3.0, 0.01, *geometry, *zeros)
        assert old == new
        blocked += old[4]
    assert blocked > 0


def _depth(part: Polygon, piece: np.ndarray) -> float:
    """Shapely's penetration depth of the convex part into a convex piece (<= 0: apart)."""
    diffs = [(q[0] - p[0], q[1] - p[1]) for p in part.exterior.coords[:-1] for q in piece]
    hull = MultiPoint(diffs).convex_hull
    origin = Point(0.0, 0.0)
    gap = hull.exterior.distance(origin)
    return gap if hull.contains(origin) else -gap


def _disc_depth(part: Polygon, disc: np.ndarray) -> float:
    centre = Point(disc[0], disc[1])
    gap = part.exterior.distance(centre)
    return disc[2] + gap if part.contains(centre) else disc[2] - gap


def _reference_excess(level: GeometricLevel, pose, slack: np.ndarray) -> float:
    """max over obstacles of (shapely's depth - the obstacle's slack): valid when <= 0."""
    a = level.arrays
    world = np.empty_like(a.part.body[0])
    pose_vertices(a.part.body[0], *pose, world)
    part = Polygon(world)
    excess = [
        _depth(part, np.unique(a.verts[p, : a.counts[p]], axis=0)) - slack[p]
        for p in range(a.verts.shape[0])
    ]
    excess += [
        _disc_depth(part, a.circles[q]) - slack[a.verts.shape[0] + q]
        for q in range(a.circles.shape[0])
    ]
    return max(excess)


def _shallow_poses(level: GeometricLevel, count: int, deepest: float) -> list:
    """Poses of the part overlapping the walls by less than ``deepest``."""
    a = level.arrays
    out = []
    for x, y, yaw in _random_poses(level.scene, 40_000, seed=11):
        c = clearance_at_pose(
            a.part.body[0], x, y, yaw, a.verts, a.counts, a.aabbs, a.circles, -np.inf
        )
        if -deepest < c < 0.0:
            out.append((x, y, yaw))
            if len(out) == count:
                break
    assert len(out) == count
    return out


def test_a_pose_is_valid_exactly_when_no_depth_exceeds_its_slack_against_shapely():
    scene = build_feeder(TABLE3)
    plain = GeometricLevel(scene)
    obstacles = plain.arrays.verts.shape[0] + plain.arrays.circles.shape[0]
    checked = 0
    for pose in _shallow_poses(plain, 120, deepest=0.15):
        depth = _reference_excess(plain, pose, np.zeros(obstacles))
        assert depth > 0.0  # shapely agrees the pose overlaps
        for factor, valid in ((0.9, False), (1.1, True)):  # the slack well below, well above
            level = GeometricLevel(scene, slack=factor * depth)
            assert level.is_valid(pose) is valid, (pose, depth, factor)
        checked += 1
    stated = relaxation_slack(scene).total
    level = GeometricLevel(scene, slack=stated)
    sides = set()
    for pose in _shallow_poses(plain, 120, deepest=0.15):
        excess = _reference_excess(plain, pose, stated)
        if abs(excess) > 1e-3:  # per obstacle: clearly inside or outside its slack
            assert level.is_valid(pose) is bool(excess < 0.0), (pose, excess)
            sides.add(bool(excess < 0.0))
    assert checked == 120 and sides == {True, False}


def test_the_stated_slack_has_its_parts():
    scene = build_feeder(TABLE3)
    slack = relaxation_slack(scene)
    labels = scene.obstacles.labels
    assert slack.contact == CONTACT_SLACK == 0.01
    assert len(slack.total) == len(labels) and np.all(slack.walls > 0.0)
    walls = dict(zip(labels, slack.walls, strict=True))
    # the exit chute's floor moves only with b (0.5% of 1.1086 at each end, +-1%);
    # the input chute's far end swings with d and theta and moves most
    assert walls["exit chute bottom"] < walls["input chute cap"]
    assert walls["exit chute bottom"] == pytest.approx(0.0055, abs=1e-4)
    assert slack.uniform == pytest.approx(CONTACT_SLACK + walls["input chute cap"])
    assert np.all(relaxation_slack(scene, tolerance=0.0).walls < 1e-12)
    with pytest.raises(ValueError, match="tolerance"):
        relaxation_slack(scene, tolerance=0.5)
    with pytest.raises(ValueError, match="slack"):
        GeometricLevel(scene, slack=-0.01)
    with pytest.raises(ValueError, match="obstacles"):
        GeometricLevel(scene, slack=[0.01, 0.02])
    level = make_level("geometric", scene, slack=slack.total)
    assert np.array_equal(level.slack, slack.total)


def _successful_drop_states(design, trials: int) -> list[np.ndarray]:
    """The states of every successful drop: the nominal feeder's, then ``trials`` perturbed
    trials as the verdict runs them (made feeder, perturbed entry, perturbed friction)."""
    nominal = build_feeder(design)
    level = DynamicLevel(nominal)
    out = []
    for orientation in ORIENTATIONS:
        result = passive_drop(nominal, orientation, level=level)
        assert result.success
        out.append(result.trajectory.states)
    make = made_feeders(design)
    for index in range(trials):
        d = draw(Perturbations(), 0, index, len(ORIENTATIONS))
        scene = make(d)
        made = DynamicLevel(scene)
        for k, orientation in enumerate(ORIENTATIONS):
            start = entry_state(
                made, scene.start(orientation), d.entry_offsets[k], d.entry_velocities[k]
            )
            result = passive_drop(scene, orientation, level=made, start=start)
            if result.success:
                out.append(result.trajectory.states)
    return out


def _invalid_fraction(level: GeometricLevel, states: list[np.ndarray]) -> float:
    poses = np.concatenate([s[:, :3] for s in states])
    return float(np.mean([not level.is_valid(q) for q in poses]))


@pytest.mark.parametrize("name", ["table3", "fig5a", "table3-wide", "table3-long"])
def test_every_pose_of_drops_that_work_is_valid_at_the_nominal_relaxed_level(name):
    design = WORKING[name]
    nominal = build_feeder(design)
    states = _successful_drop_states(design, trials=3)
    assert len(states) >= 6
    relaxed = GeometricLevel(nominal, slack=relaxation_slack(nominal).total)
    assert _invalid_fraction(relaxed, states) == 0.0
    # the paper's Eq. 9 (slack 0) refuses a large share of the same poses (issue 21: 28-52%)
    assert _invalid_fraction(GeometricLevel(nominal), states) > 0.2


@pytest.mark.slow
@pytest.mark.parametrize("name", ["table3", "fig5a", "table3-wide", "table3-long"])
def test_every_pose_of_many_perturbed_drops_is_valid_at_the_relaxed_level(name):
    design = WORKING[name]
    nominal = build_feeder(design)
    states = _successful_drop_states(design, trials=30)
    relaxed = GeometricLevel(nominal, slack=relaxation_slack(nominal).total)
    assert _invalid_fraction(relaxed, states) == 0.0


@pytest.mark.parametrize("name", ["table3", "fig5a", "table3-wide", "table3-long"])
def test_the_entry_region_is_valid_at_the_relaxed_level(name):
    """Planning starts from the entry region: every perturbed entry of the verdict (in its
    made feeder) and the nominal start offset to the corners of the entry box
    (+-0.05 in x, y and yaw) are valid poses of the nominal design's relaxed level."""
    design = WORKING[name]
    nominal = build_feeder(design)
    relaxed = GeometricLevel(nominal, slack=relaxation_slack(nominal).total)
    make = made_feeders(design)
    for index in range(40):
        d = draw(Perturbations(), 1, index, len(ORIENTATIONS))
        scene = make(d)
        made = DynamicLevel(scene)
        for k, orientation in enumerate(ORIENTATIONS):
            start = entry_state(
                made, scene.start(orientation), d.entry_offsets[k], d.entry_velocities[k]
            )
            assert relaxed.is_valid(start[:3]), (index, orientation)
    p = Perturbations()
    for orientation in ORIENTATIONS:
        x, y, yaw = nominal.start(orientation)
        assert GeometricLevel(nominal).is_valid((x, y, yaw))  # the planning problem's start
        for sx in (-1, 1):
            for sy in (-1, 1):
                for sw in (-1, 1):
                    corner = (x + sx * p.position, y + sy * p.position, yaw + sw * p.yaw)
                    assert relaxed.is_valid(corner), (orientation, sx, sy, sw)


def test_shapely_reference_measures_a_known_overlap():
    """The reference itself: a unit square pushed 0.1 into another is 0.1 deep."""
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    part = Polygon(square + np.array([0.9, 0.3]))
    assert _depth(part, square) == pytest.approx(0.1)
    assert _depth(Polygon(square + np.array([1.2, 0.0])), square) == pytest.approx(-0.2)
    assert shapely.is_valid(part)
