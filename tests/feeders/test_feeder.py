"""Specification of feeders.feeder: the device built from a design (paper Fig. 1, Tables 1-2).

References: shapely as an independent geometry implementation (validity, areas, containment,
distances), Table 1's definitions (g the lower left corner of the input chute, e the x of the
left cavity wall, f and r the protuberance tip, theta the chute angle) and the twelve names
typed from the paper. Sampled designs come from the seeded Halton sequence (seed 0).
"""

from __future__ import annotations

import collections
import dataclasses
import math
import re

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString, Point, Polygon, box

from feeders.design import (
    DESIGN_SPACE,
    PARAMETER_NAMES,
    PHYSICAL_BOUNDS,
    PRESETS,
    DesignParameters,
    DesignSpace,
)
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.halton import halton_designs, halton_points
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import Scene

NAMES = {"a", "b", "c", "d", "e", "fx", "fy", "gx", "gy", "r", "theta", "alpha"}
N_HALTON = 2000
TABLE3 = PRESETS["table3"]


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))


def _part_polygon(part: Peg, pose) -> Polygon:
    """The part at a pose, placed with shapely's affine transforms (independent of the code)."""
    x, y, yaw = pose
    body = Polygon(part.body_vertices())
    turned = shapely.affinity.rotate(body, yaw, origin=(0.0, 0.0), use_radians=True)
    return shapely.affinity.translate(turned, x, y)


def _roof_height(d: DesignParameters) -> float:
    """The cavity roof: the height of the input chute's upper wall where it ends above the lip
    g (the chute is a strip of width a rising at theta from its floor through g)."""
    return d.gy + d.a * math.cos(d.theta)


def _geometry_problems(scene: Scene) -> list[str]:
    """Every way the built scene disagrees with the device's specification, checked with
    shapely; an empty list means the geometry is sound."""
    d, part = scene.design, scene.part
    problems: list[str] = []
    interior = Polygon(scene.outline)
    if not (interior.is_valid and interior.exterior.is_simple):
        return [f"free interior is not a valid simple polygon: {shapely.is_valid_reason(interior)}"]
    if not interior.exterior.is_ccw:
        problems.append("free interior outline is not counter-clockwise")

    labels = scene.obstacles.labels
    polygons = scene.obstacles.polygons
    pairs = list(zip(labels, polygons, strict=False))  # labels: polygons, then the disc
    finger = [Polygon(p) for label, p in pairs if label == "protuberance finger"]
    walls = [(label, Polygon(p)) for label, p in pairs if label != "protuberance finger"]
    if len(finger) != 1 or len(walls) != len(scene.outline):
        problems.append("expected one wall per outline edge and one protuberance finger")
    for label, wall in walls:
        overlap = wall.intersection(interior).area
        if overlap > 1e-9:
            problems.append(f"wall '{label}' overlaps the free interior by {overlap:.3g}")

    # The protuberance: tip disc (f, r), inside the interior except where it grows out of the
    # left side of the cavity (left wall, left floor, left chamfer: x <= -b/2, 0 <= y < roof).
    circles = scene.obstacles.circles
    if circles.shape != (1, 3) or not np.allclose(circles[0], [d.fx, d.fy, d.r], atol=1e-12):
        problems.append(f"tip disc {circles.tolist()} is not (f, r)")
    tip = Point(d.fx, d.fy)
    if not interior.contains(tip):
        problems.append("protuberance tip centre f is not inside the free interior")
    left_side = box(-1e6, 0.0, -d.b / 2, _roof_height(d) - 1e-9)
    touched = interior.exterior.intersection(tip.buffer(d.r - 1e-9, quad_segs=256))
    stray = touched.difference(left_side)
    if stray.length > 1e-9:
        problems.append(f"protuberance tip reaches a wall other than the left side: {stray}")

    solids = [wall for _, wall in walls] + finger
    for name, pose in scene.starts.items():
        polygon = _part_polygon(part, pose)
        if not interior.buffer(1e-9).contains(polygon):
            problems.append(f"start '{name}' is not inside the free interior")
        gaps = [polygon.distance(s) for s in solids] + [polygon.distance(tip) - d.r]
        if min(gaps) <= 0.0:
            problems.append(f"start '{name}' touches an obstacle (gap {min(gaps):.3g})")

    goal = scene.goal
    if not (-d.b / 2 - 1e-12 <= goal.x_min < goal.x_max <= d.b / 2 + 1e-12):
        problems.append(f"goal x [{goal.x_min}, {goal.x_max}] is not inside |x| <= b/2")
    if not goal.y_max < 0.0:
        problems.append(f"goal y_max = {goal.y_max} is not below the top of the exit chute")
    if not interior.buffer(1e-9).contains(box(goal.x_min, goal.y_min, goal.x_max, goal.y_max)):
        problems.append("goal box is not inside the free interior")
    if not interior.buffer(1e-9).contains(_part_polygon(part, goal.target)):
        problems.append("the part at the goal target does not fit in the exit chute")
    if not math.isclose(goal.yaw, -math.pi / 2, abs_tol=1e-12):
        problems.append(f"goal yaw {goal.yaw} is not -pi/2 (heavy end down)")
    return problems


@pytest.fixture(scope="module")
def halton_outcomes():
    """Each of the 2,000 Halton designs (seed 0) with its scene or the exception it raised."""
    outcomes = []
    for design in halton_designs(N_HALTON, seed=0):
        try:
            outcomes.append((design, build_feeder(design)))
        except Exception as exc:  # the test below says which kinds are allowed
            outcomes.append((design, exc))
    return outcomes


def _reason_kind(reason: str) -> str:
    """A rejection reason with its numbers blanked, to count reasons of the same kind."""
    return re.sub(r"-?\d+(\.\d+)?(e-?\d+)?", "#", reason)


# --- sampled designs ------------------------------------------------------------------------


def test_halton_designs_build_or_are_degenerate_with_named_parameters(halton_outcomes):
    """Every design of the Table 2 box either builds or raises DegenerateDesign naming a
    non-empty subset of the twelve parameters (paper Table 1); no other exception."""
    bad = []
    kinds: collections.Counter[str] = collections.Counter()
    built = 0
    for design, outcome in halton_outcomes:
        if isinstance(outcome, Scene):
            built += 1
            continue
        if not isinstance(outcome, DegenerateDesign):
            bad.append(f"{design}: {type(outcome).__name__}: {outcome}")
            continue
        params = outcome.parameters
        if not (isinstance(params, tuple) and params and set(params) <= NAMES):
            bad.append(f"{design}: parameters {params!r}")
        if not outcome.reason or outcome.reason not in str(outcome):
            bad.append(f"{design}: message {str(outcome)!r} lacks reason {outcome.reason!r}")
        kinds[_reason_kind(outcome.reason)] += 1
    summary = f"{built}/{len(halton_outcomes)} = {built / len(halton_outcomes):.1%} build; " + (
        f"rejections: {kinds.most_common(5)}"
    )
    assert not bad, f"{len(bad)} bad outcomes, first: {bad[:3]}; {summary}"
    assert built >= len(halton_outcomes) // 2, summary


@pytest.mark.slow  # ~9 s
def test_every_built_halton_design_has_sound_geometry(halton_outcomes):
    """Reference: shapely checks of _geometry_problems on every design that builds."""
    failures = [
        (design, problems)
        for design, outcome in halton_outcomes
        if isinstance(outcome, Scene)
        for problems in [_geometry_problems(outcome)]
        if problems
    ]
    assert not failures, f"{len(failures)} designs, first: {failures[:2]}"


def test_sweep_beyond_the_box_builds_sound_geometry_or_is_degenerate():
    """Designs around the Table 2 box (each range widened by half its width on both sides,
    e.g. theta down to 0, the paper's own Fig. 5 goes below the box) either build with sound
    geometry or raise DegenerateDesign. Sampled with the seeded Halton sequence (seed 3)."""
    widened = []
    for name, (lo, hi) in zip(PARAMETER_NAMES, DESIGN_SPACE.bounds, strict=True):
        plo, phi = PHYSICAL_BOUNDS[name]
        widened.append((max(lo - (hi - lo) / 2, plo), min(hi + (hi - lo) / 2, phi)))
    failures = []
    for row in halton_points(1000, seed=3, space=DesignSpace(tuple(widened))):
        design = DesignParameters.from_vector(row)
        try:
            scene = build_feeder(design)
        except DegenerateDesign:
            continue
        problems = _geometry_problems(scene)
        if problems:
            failures.append((design, problems))
    assert not failures, f"{len(failures)} designs, first: {failures[:2]}"


# --- presets --------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_every_preset_builds_with_sound_geometry(name):
    """Reference: shapely checks of _geometry_problems."""
    scene = build_feeder(PRESETS[name])
    assert scene.design == PRESETS[name]
    assert _geometry_problems(scene) == []


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_outline_has_the_table1_landmarks(name):
    """Reference: Table 1: g is the lower left corner of the input chute (a vertex); the left
    cavity wall is the vertical line x = e; the input chute's top end is d along the chute at
    angle theta from g, and the chute is a wide there. The exit chute walls are x = -b/2, b/2
    down to its bottom, twice the part length (reconstruction, feeders/feeder.py)."""
    d = PRESETS[name]
    scene = build_feeder(d)
    vertices = [tuple(v) for v in scene.outline]

    def has_vertex(x, y):
        return any(math.isclose(vx, x, abs_tol=1e-9) and math.isclose(vy, y, abs_tol=1e-9)
                   for vx, vy in vertices)  # fmt: skip

    u = np.array([math.cos(d.theta), math.sin(d.theta)])
    n = np.array([-math.sin(d.theta), math.cos(d.theta)])
    top_floor = np.array([d.gx, d.gy]) + d.d * u
    assert has_vertex(d.gx, d.gy)
    assert has_vertex(*top_floor)
    assert has_vertex(*(top_floor + d.a * n))
    assert has_vertex(d.e, _roof_height(d))
    depth = 2 * DEFAULT_PEG.length
    assert has_vertex(-d.b / 2, -depth) and has_vertex(d.b / 2, -depth)
    assert min(v[1] for v in vertices) == pytest.approx(-depth)
    assert min(v[0] for v in vertices) == pytest.approx(d.e)


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_start_poses_point_along_the_input_chute(name):
    """heavy_trailing points up the chute (yaw = theta), heavy_leading down it (yaw = theta - pi
    wrapped); both place the part's middle on the chute's centre line (a/2 from the floor)."""
    d = PRESETS[name]
    scene = build_feeder(d)
    assert set(scene.starts) == {"heavy_leading", "heavy_trailing"}
    leading, trailing = scene.starts["heavy_leading"], scene.starts["heavy_trailing"]
    assert abs(_wrap(leading[2] - (d.theta - math.pi))) < 1e-12
    assert -math.pi <= leading[2] < math.pi
    assert trailing[2] == pytest.approx(d.theta, abs=1e-12)
    middles = []
    for x, y, yaw in (leading, trailing):
        middle = np.array([x, y]) - DEFAULT_PEG.com_offset * np.array(
            [math.cos(yaw), math.sin(yaw)]
        )
        middles.append(middle)
        far = (d.gx + 100 * math.cos(d.theta), d.gy + 100 * math.sin(d.theta))
        floor = LineString([(d.gx, d.gy), far])
        assert floor.distance(Point(middle)) == pytest.approx(d.a / 2, abs=1e-9)
    np.testing.assert_allclose(middles[0], middles[1], atol=1e-12)
    # heavy leading: the heavy end (body +x) is the lower end of the part in the chute
    for pose, heavy_lower in ((leading, True), (trailing, False)):
        polygon = np.array(_part_polygon(DEFAULT_PEG, pose).exterior.coords)[:4]
        body = DEFAULT_PEG.body_vertices()
        heavy_y = polygon[body[:, 0] > 0, 1].mean()
        light_y = polygon[body[:, 0] < 0, 1].mean()
        assert (heavy_y < light_y) == heavy_lower


def test_goal_is_heavy_end_down_in_the_exit_chute():
    """At yaw -pi/2 the body's +x end (the heavy end) is straight below the centre of mass."""
    scene = build_feeder(TABLE3)
    goal = scene.goal
    assert goal.yaw == pytest.approx(-math.pi / 2, abs=1e-12)
    assert 0 < goal.yaw_tol < math.pi / 2
    polygon = np.array(_part_polygon(DEFAULT_PEG, goal.target).exterior.coords)[:4]
    body = DEFAULT_PEG.body_vertices()
    heavy_end = polygon[body[:, 0] > 0].mean(axis=0)
    assert heavy_end[0] == pytest.approx(goal.target[0], abs=1e-12)
    assert heavy_end[1] < goal.target[1]
    assert goal.contains(goal.target)
    assert not goal.contains((goal.target[0], goal.target[1], math.pi / 2))  # heavy end up
    assert goal.x_max <= TABLE3.b / 2 and goal.x_min >= -TABLE3.b / 2
    assert goal.y_max < 0.0 < TABLE3.c  # below the cavity floor and the chute's mouth


def test_scene_carries_the_physical_settings():
    part = Peg.two_density(length=2.2, width=0.9)
    scene = build_feeder(TABLE3, part, friction=0.45, gravity=(0.0, -3.0), name="x")
    assert (scene.part, scene.friction, scene.gravity, scene.name) == (part, 0.45, (0.0, -3.0), "x")
    xmin, xmax, ymin, ymax = scene.bounds
    assert (xmin, ymin) == pytest.approx(tuple(scene.outline.min(axis=0)))
    assert (xmax, ymax) == pytest.approx(tuple(scene.outline.max(axis=0)))
    assert _geometry_problems(scene) == []


# --- hand-made degenerate designs -----------------------------------------------------------


def _rejection(design: DesignParameters, part: Peg = DEFAULT_PEG) -> DegenerateDesign:
    with pytest.raises(DegenerateDesign) as info:
        build_feeder(design, part)
    exc = info.value
    assert exc.reason and exc.reason in str(exc)
    assert exc.parameters and set(exc.parameters) <= NAMES
    for name in exc.parameters:
        assert name in str(exc)
    return exc


def test_part_wider_than_the_input_chute():
    """table3 has a = 1.1: a peg 1.105 wide cannot enter the input chute."""
    exc = _rejection(TABLE3, Peg.two_density(width=1.105))
    assert exc.parameters == ("a",)


def test_part_wider_than_the_exit_chute_only():
    """fig6a has a = 1.178 > b = 1.1: a peg 1.15 wide enters but cannot leave."""
    exc = _rejection(PRESETS["fig6a"], Peg.two_density(width=1.15))
    assert exc.parameters == ("b",)


def test_input_chute_shorter_than_the_part():
    exc = _rejection(dataclasses.replace(TABLE3, d=DEFAULT_PEG.length))
    assert exc.parameters == ("d",)


@pytest.mark.parametrize(
    ("tip", "wall_parameters"),
    [
        # below the left cavity floor (y = c = 0.7979): the floor is placed by c
        ({"fx": -1.5, "fy": 0.3}, {"c"}),
        # left of the left cavity wall (x = e = -1.9)
        ({"fx": -2.2}, {"e"}),
        # under the left chamfer (from (-b/2, 0) up at alpha): placed by b, c, alpha
        ({"fx": -0.8, "fy": 0.2}, {"b", "alpha"}),
        # above the cavity roof (at gy + a cos(theta) = 3.0209): placed by gy, a, theta
        ({"fy": 3.3}, {"gy", "a", "theta"}),
    ],
)
def test_protuberance_tip_inside_a_wall(tip, wall_parameters):
    """The rejection names f and at least one parameter that places the wall the tip is in
    (walls as defined in Table 1 and the reconstruction in feeders/feeder.py)."""
    exc = _rejection(dataclasses.replace(TABLE3, **tip))
    assert {"fx", "fy"} <= set(exc.parameters)
    assert wall_parameters & set(exc.parameters), exc.parameters


def test_protuberance_touching_the_roof():
    """Tip half a radius below the roof (reference height gy + a cos(theta))."""
    design = dataclasses.replace(TABLE3, fy=_roof_height(TABLE3) - TABLE3.r / 2)
    exc = _rejection(design)
    assert {"fy", "r"} <= set(exc.parameters)
    assert "roof" in exc.reason


def test_protuberance_touching_the_wall_below_the_lip():
    """Tip half a radius left of the lip's vertical face x = gx, halfway up it."""
    design = dataclasses.replace(TABLE3, fx=TABLE3.gx - TABLE3.r / 2, fy=1.6)
    exc = _rejection(design)
    assert {"fx", "fy", "r", "gx"} <= set(exc.parameters)


def test_protuberance_just_clear_of_the_roof_builds():
    """The boundary of the previous case: a tip 1e-6 below touching builds (and is sound)."""
    design = dataclasses.replace(TABLE3, fy=_roof_height(TABLE3) - TABLE3.r - 1e-6)
    assert _geometry_problems(build_feeder(design)) == []


def test_lip_below_the_cavity_floor():
    exc = _rejection(dataclasses.replace(TABLE3, gy=0.7))
    assert set(exc.parameters) == {"gy", "c"}


def test_lip_far_left_makes_walls_cross():
    """g left of the left cavity wall: the underside of the lip crosses the cavity walls."""
    exc = _rejection(dataclasses.replace(TABLE3, gx=-3.0))
    assert "gx" in exc.parameters and "e" in exc.parameters


def test_left_cavity_wall_right_of_the_exit_chute_is_degenerate():
    """e > -b/2 puts the left cavity wall inside the exit chute's mouth: the cavity's left side
    would fold back into the chute. Either rejected naming e, or built with sound geometry."""
    design = dataclasses.replace(TABLE3, e=-0.5, fx=-0.3)  # b/2 = 0.5543
    try:
        scene = build_feeder(design)
    except DegenerateDesign as exc:
        assert "e" in exc.parameters
    else:
        assert _geometry_problems(scene) == []


def test_sharp_lip_keeps_its_walls_out_of_the_input_chute():
    """A lip overhanging the exit chute (g.x < b/2) with a shallow chute (theta = 0.1) is a
    solid wedge sharper than a right angle; its walls must not poke into the free interior."""
    design = dataclasses.replace(TABLE3, gx=0.2, theta=0.1)
    try:
        scene = build_feeder(design)
    except DegenerateDesign as exc:
        assert {"gx", "theta"} & set(exc.parameters)
    else:
        assert _geometry_problems(scene) == []
