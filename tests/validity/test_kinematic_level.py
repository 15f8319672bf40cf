"""The kinematic level (paper Eq. 8, Algorithm 2) as a specification.

References: the closed form ``q + T u`` for free motion; hand-worked bounces of a peg whose
striking corner lies straight below its centre of mass (the impact then acts as on a point
mass: ``v_n+ = -e v_n-``, ``v_t+ = v_t - mu (1 + e) |v_n|`` while slipping); shapely for
whether the part overlaps an obstacle at the states the level visits; and the energy bound
of a dissipative impact (no state moves faster than the input that drives it).
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest
import shapely

from feeders.design import PRESETS
from feeders.feeder import WALL_THICKNESS, DegenerateDesign, build_feeder
from feeders.halton import halton_designs
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import Goal, InputSet, Scene
from feeders.shapes import Obstacles
from validity.kinematic import KinematicLevel
from validity.pose_samples import cross_check_poses

AREA_TOL = 1e-12  # shapely intersection area still counted as touching (length^2)
BODY = DEFAULT_PEG.body_vertices()
FLOOR = np.array([[-50.0, -1.0], [50.0, -1.0], [50.0, 0.0], [-50.0, 0.0]])


def _scene(polygons, circles=None, part=DEFAULT_PEG, **physics) -> Scene:
    return Scene(
        name="test",
        obstacles=Obstacles(
            tuple(np.asarray(p, dtype=float) for p in polygons),
            np.zeros((0, 3)) if circles is None else circles,
        ),
        part=part,
        bounds=(-40.0, 40.0, -40.0, 40.0),
        starts={"start": (0.0, 5.0, 0.0)},
        goal=Goal(x_min=-1.0, x_max=1.0, y_min=-1.0, y_max=1.0, yaw=0.0, yaw_tol=0.5),
        **physics,
    )


@functools.cache
def _table3() -> Scene:
    return build_feeder(PRESETS["table3"], name="table3")


def _polygons(states: np.ndarray) -> np.ndarray:
    c, s = np.cos(states[:, 2]), np.sin(states[:, 2])
    x = states[:, :1] + c[:, None] * BODY[:, 0] - s[:, None] * BODY[:, 1]
    y = states[:, 1:2] + s[:, None] * BODY[:, 0] + c[:, None] * BODY[:, 1]
    return shapely.polygons(np.stack([x, y], axis=-1))


def _overlap(scene: Scene, states: np.ndarray) -> np.ndarray:
    """Shapely: overlap area of the part with the polygons at each state, +inf where it is
    closer than its radius to a disc centre."""
    parts = _polygons(states)
    solid = shapely.unary_union([shapely.Polygon(p) for p in scene.obstacles.polygons])
    area = shapely.area(shapely.intersection(parts, solid))
    for cx, cy, r in scene.obstacles.circles:
        inside = shapely.distance(parts, shapely.Point(cx, cy)) < r - 1e-9
        area = np.where(inside, np.inf, area)
    return area


def _corner_down_pose(height: float) -> tuple[float, float, float]:
    """The pose whose corner 0 is straight below the centre of mass, ``height`` above y = 0."""
    bx, by = BODY[0]
    yaw = -math.pi / 2 - math.atan2(by, bx)
    return (0.0, height + math.hypot(bx, by), yaw)


# --------------------------------------------------------------------------- free motion


def test_free_motion_is_q_plus_T_u_with_the_commanded_velocity() -> None:
    level = KinematicLevel(_scene([]))
    for u in [(1.0, -0.5, 0.3), (-1.0, 1.0, -1.0), (0.0, 0.0, 0.0)]:
        out = level.propagate((0.5, 2.0, 0.1, 9.0, 9.0, 9.0), u, 1.3)
        assert out[:2] == pytest.approx((0.5 + 1.3 * u[0], 2.0 + 1.3 * u[1]), abs=1e-12)
        assert out[2] == pytest.approx(0.1 + 1.3 * u[2], abs=1e-12)
        assert out[3:] == pytest.approx(u, abs=0.0)  # Eq. 8: v = u, whatever v was before


# --------------------------------------------------------------------------- impacts


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_head_on_bounce_off_a_floor_is_the_point_mass_bounce(e: float) -> None:
    """A corner straight below the centre of mass, 0.004 above a frictionless floor, driven
    down at 1: it touches after 0.004 s, leaves at e, and rises for the rest of the 0.01 s step
    (contact band 1e-9, so the touch is exact to 1e-9)."""
    level = KinematicLevel(_scene([FLOOR], friction=0.0, restitution=e), contact_band=1e-9)
    x, y, yaw = _corner_down_pose(0.004)
    out = level.propagate((x, y, yaw, 0.0, 0.0, 0.0), (0.0, -1.0, 0.0), 0.01)
    assert out[1] == pytest.approx(y - 0.004 + e * 0.006, abs=2e-9)
    assert out[4] == pytest.approx(e, abs=1e-12)
    assert out[3] == pytest.approx(0.0, abs=1e-12) and out[5] == pytest.approx(0.0, abs=1e-12)


def test_oblique_bounce_with_friction_sticks_and_spins_the_peg() -> None:
    """Driven at (0.5, -1) with mu = 0.3, e = 0.5 onto a corner a distance d straight below the
    centre of mass. At the corner a tangential impulse p changes the slip by p k_tt,
    k_tt = 1/m + d^2/I = 5.9, so mu (1 + e) |v_n| k_tt m = 2.6 > 0.5: the slip stops and the
    corner sticks (Routh's stick branch). Hand-worked: p_t = -0.5 / k_tt,
    v_x+ = 0.5 + p_t / m, omega+ = -d p_t / I... with the corner's horizontal velocity 0, and
    v_y+ = e = 0.5 (the normal impulse acts through the centre of mass)."""
    level = KinematicLevel(_scene([FLOOR], friction=0.3, restitution=0.5), contact_band=1e-9)
    x, y, yaw = _corner_down_pose(0.004)
    d = math.hypot(*BODY[0])
    m, inertia = DEFAULT_PEG.mass, DEFAULT_PEG.inertia
    k_tt = 1.0 / m + d * d / inertia
    out = level.propagate((x, y, yaw, 0.0, 0.0, 0.0), (0.5, -1.0, 0.0), 0.01)
    vx = 0.5 - 0.5 / (m * k_tt)
    assert out[3] == pytest.approx(vx, abs=1e-12)
    assert out[4] == pytest.approx(0.5, abs=1e-12)
    assert out[3] + out[5] * d == pytest.approx(0.0, abs=1e-12)  # the corner does not slip
    assert out[0] == pytest.approx(x + 0.5 * 0.004 + vx * 0.006, abs=2e-9)


def test_each_step_starts_again_from_the_commanded_velocity() -> None:
    """Eq. 8: v^{l+1} = u^{l+1}. After a bounce the next step drives down again, so a part
    pushed into a floor keeps touching it and never climbs away (plastic: it stays on it)."""
    level = KinematicLevel(_scene([FLOOR], friction=0.0, restitution=0.0))
    x, y, yaw = _corner_down_pose(0.02)
    run = level.run((x, y, yaw, 0.0, 0.0, 0.0), (0.0, -1.0, 0.0), 1.0, record=True)
    lowest = np.array([shapely.bounds(p)[1] for p in _polygons(run.states)])
    assert lowest[-1] == pytest.approx(0.0, abs=level.contact_band)
    assert run.summary["impacts"] >= 90  # it presses on the floor almost every step
    assert np.all(lowest >= 0.0)


def test_a_part_pressed_into_a_wall_slides_along_it_slower_than_commanded() -> None:
    """Driven diagonally into a floor, flat: friction at each impact takes speed off the
    slide; the part moves right, never sinks, and gains no speed beyond the input."""
    level = KinematicLevel(_scene([FLOOR], friction=0.3, restitution=0.3))
    start = (0.0, 0.5 + 1e-3, 0.0, 0.0, 0.0, 0.0)
    run = level.run(start, (1.0, -1.0, 0.0), 2.0, record=True)
    assert 0.0 < run.final[0] < 2.0
    assert np.all(_overlap(level.scene, run.states) <= AREA_TOL)
    assert run.summary["impacts"] > 0


BOX = Peg(length=2.0, width=1.0, mass=1.0, com_offset=0.0, inertia=5.0 / 12.0)  # uniform
WALL = np.array([[3.0, -20.0], [4.0, -20.0], [4.0, 20.0], [3.0, 20.0]])  # its face: x = 3


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("yaw", [0.0, math.pi / 2], ids=["short_face", "long_face"])
def test_a_box_driven_flat_into_a_wall_leaves_at_minus_e_without_spin(e, yaw) -> None:
    """Issue 11, fault 2, through Eq. 8's stepper: a uniform 2 x 1 box driven at (1, 0, 0)
    into a frictionless wall with a face parallel to it, 0.004 away, touches after 0.004 s at
    two corners at once and by symmetry (point-mass impact) leaves at (-e, 0, 0) without spin,
    moving back for the rest of the 0.01 s step (contact band 1e-9). Sequential single-point
    impacts spun it (and jammed on the long face at e = 0)."""
    level = KinematicLevel(_scene([WALL], part=BOX, friction=0.0, restitution=e), contact_band=1e-9)
    half = 1.0 if yaw == 0.0 else 0.5  # the centre's distance to the face that hits
    x0 = 3.0 - half - 0.004
    run = level.run((x0, 0.0, yaw, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 0.01, record=False)
    assert run.summary["jams"] == 0  # not stopped by the jam limit
    assert run.summary["simultaneous_impacts"] >= 1  # both corners resolved together
    assert run.summary["impact_frictionless_fallbacks"] == 0
    assert run.summary["impact_lcp_failures"] == 0
    out = level.propagate((x0, 0.0, yaw, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 0.01)
    assert out == pytest.approx(tuple(run.final), abs=0.0)
    assert out[3:] == pytest.approx((-e, 0.0, 0.0), abs=1e-12)
    assert out[0] == pytest.approx(x0 + 0.004 - e * 0.006, abs=2e-9)
    assert out[1] == pytest.approx(0.0, abs=1e-12) and out[2] == pytest.approx(yaw, abs=1e-12)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_box_driven_flat_onto_a_floor_slips_and_bounces_without_spin(e: float) -> None:
    """The uniform box, long face down 0.004 above a floor with mu = 0.2, driven at
    (0.4, -1, 0): both lower corners land at once after 0.004 s. Hand-worked (both corners
    stay pressed, the slip never stops: mu (1 + e) <= 0.4): v+ = (0.4 - mu (1 + e), e, 0), then
    it moves with v+ for the remaining 0.006 s."""
    level = KinematicLevel(
        _scene([FLOOR], part=BOX, friction=0.2, restitution=e), contact_band=1e-9
    )
    out = level.propagate((0.0, 0.504, 0.0, 0.0, 0.0, 0.0), (0.4, -1.0, 0.0), 0.01)
    vx = 0.4 - 0.2 * (1.0 + e)
    assert out[3:] == pytest.approx((vx, e, 0.0), abs=1e-12)
    assert out[0] == pytest.approx(0.4 * 0.004 + vx * 0.006, abs=2e-9)
    assert out[1] == pytest.approx(0.5 + e * 0.006, abs=2e-9)
    assert out[2] == pytest.approx(0.0, abs=1e-12)


# --------------------------------------------------------------------------- tunnelling


def test_no_tunnelling_through_the_thinnest_wall_of_1000_halton_designs() -> None:
    """For each of 1,000 Halton designs that build, a slab as thin as the design's thinnest
    solid (the protuberance, 2r >= 0.2, or a wall, 0.4) is shot at by the peg from 0.5 above, at a
    random yaw, at the top speed of U and top turn rate, with U so fast (max_speed 300) that
    one step of h = 0.01 is 3 long, several times the slab: not one shot ends on the other
    side, and no state after any step overlaps the slab (shapely, area <= 1e-12)."""
    rng = np.random.default_rng(2026)
    widths = []
    for design in halton_designs(1000, seed=1):
        try:
            build_feeder(design)
        except DegenerateDesign:
            continue
        widths.append(min(2.0 * design.r, WALL_THICKNESS))  # protuberance, or a wall
    assert len(widths) >= 500, f"only {len(widths)} of 1000 designs build"
    crossed, overlapping = 0, 0
    fast = InputSet(max_speed=300.0, max_turn=300.0)
    for w in widths:
        slab = np.array([[-20.0, -w], [20.0, -w], [20.0, 0.0], [-20.0, 0.0]])
        scene = _scene([slab], inputs=fast)
        level = KinematicLevel(scene)
        yaw = rng.uniform(-math.pi, math.pi)
        c, s = math.cos(yaw), math.sin(yaw)
        drop = -min(s * bx + c * by for bx, by in BODY)  # centre above the lowest corner
        start = (rng.uniform(-1, 1), 0.5 + drop, yaw, 0.0, 0.0, 0.0)
        u = (0.0, -fast.max_speed, rng.choice((-1.0, 1.0)) * fast.max_turn)
        run = level.run(start, u, 0.05, record=True)
        crossed += int(np.any(run.states[:, 1] < -w))  # centre of mass below the slab
        overlapping += int(np.any(_overlap(scene, run.states) > AREA_TOL))
    assert crossed == 0 and overlapping == 0, f"{crossed=} {overlapping=} of {len(widths)}"


def test_the_tunnelling_check_has_teeth() -> None:
    """The same shot, propagated by free motion (no collision handling), ends below the slab:
    so ``crossed`` above would count a tunnel."""
    level = KinematicLevel(_scene([], inputs=InputSet(max_speed=300.0)))
    out = level.propagate((0.0, 0.5 + 0.8, 0.0, 0, 0, 0), (0.0, -300.0, 0.0), 0.05)
    assert out[1] < -0.4


@pytest.mark.slow  # ~6 s
def test_no_overlap_after_any_step_in_real_feeders_at_top_speed() -> None:
    """From valid states of table3 and 40 Halton designs, random controls at the corners of a
    fast U (one step moves up to 0.3 + R * 0.3): every state after every step is free of
    overlap (shapely, area <= 1e-12), and no speed exceeds the input's energy bound."""
    rng = np.random.default_rng(3)
    scenes = [_table3()]
    for design in halton_designs(80, seed=5):
        try:
            scenes.append(build_feeder(design))
        except DegenerateDesign:
            continue
    checked = 0
    for scene in scenes[:41]:
        scene = dataclasses.replace(scene, inputs=InputSet(max_speed=30.0, max_turn=30.0))
        level = KinematicLevel(scene)
        poses = cross_check_poses(scene, 400, int(rng.integers(1 << 30)))
        inside = shapely.contains_xy(shapely.Polygon(scene.outline), poses[:, 0], poses[:, 1])
        poses = [p for p in poses[inside] if level.is_valid(level.state_of_pose(p))][:10]
        for pose in poses:
            u = rng.choice((-1.0, 1.0), 3) * np.array([30.0, 30.0, 30.0])
            run = level.run(level.state_of_pose(pose), u, 0.2, record=True)
            area = _overlap(scene, run.states)
            assert np.all(area <= AREA_TOL), f"{scene.name} {pose=} {u=}: {area.max():.3g}"
            assert all(level.is_valid(s) for s in run.states)
            checked += len(run.states)
    assert checked >= 3000


# --------------------------------------------------------------------------- energy, validity


def test_impacts_never_leave_the_part_faster_than_its_input() -> None:
    """Kinetic energy after every step (post-impact velocity) is at most the commanded
    velocity's, in table3 from its starts and random valid poses."""
    scene = _table3()
    level = KinematicLevel(scene)
    rng = np.random.default_rng(11)
    m, inertia = level.mass, level.inertia
    impacts = 0
    for orientation in ("heavy_leading", "heavy_trailing"):
        state = level.state_of_pose(scene.start(orientation))
        for _ in range(60):
            u = rng.uniform(*level.control_bounds())
            run = level.run(state, u, 0.2, record=True)
            v = run.states[1:, 3:]
            energy = 0.5 * m * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * inertia * v[:, 2] ** 2
            commanded = 0.5 * m * (u[0] ** 2 + u[1] ** 2) + 0.5 * inertia * u[2] ** 2
            assert np.all(energy <= commanded + 1e-12)
            impacts += run.summary["impacts"]
            state = tuple(run.final)
    assert impacts > 100


def test_validity_is_exact_non_penetration_bounds_and_the_speed_limit() -> None:
    level = KinematicLevel(_scene([FLOOR]))
    lying = DEFAULT_PEG.width / 2  # height of the centre of mass of the peg lying on the floor
    assert level.is_valid((0.0, lying, 0.0, 0.0, 0.0, 0.0))  # touching the floor
    assert not level.is_valid((0.0, lying - 1e-9, 0.0, 0.0, 0.0, 0.0))
    assert not level.is_valid((0.0, 5.0, 0.0, 0.0, 0.0, level.velocity_limit * 1.01))
    assert not level.is_valid((45.0, 5.0, 0.0, 0.0, 0.0, 0.0))


def test_the_velocity_limit_is_the_energy_bound_of_U() -> None:
    """sqrt(2 E_max / min(m, I)), E_max = m s^2 + I w^2 / 2 for |vx|, |vy| <= s, |w| <= w."""
    scene = _scene([], inputs=InputSet(max_speed=2.0, max_turn=0.5))
    level = KinematicLevel(scene)
    m, i = DEFAULT_PEG.mass, DEFAULT_PEG.inertia
    expected = math.sqrt((2 * m * 4.0 + i * 0.25) / min(m, i))
    assert level.velocity_limit == pytest.approx(expected, rel=1e-8)


@pytest.mark.parametrize(
    "option,value",
    [
        ("step", 0.0),
        ("step", 2.0),
        ("contact_band", 0.0),
        ("contact_band", 1.0),
        ("max_impacts", 0),
    ],
)
def test_bad_options_name_the_option_and_the_range(option: str, value: float) -> None:
    with pytest.raises(ValueError, match="allowed range"):
        KinematicLevel(_scene([]), **{option: value})


def test_a_scene_refuses_a_restitution_outside_0_1() -> None:
    with pytest.raises(ValueError, match=r"restitution.*\[0, 1\]"):
        _scene([], restitution=1.5)


def test_telemetry_counts_impacts_only_where_the_part_meets_a_wall() -> None:
    level = KinematicLevel(_scene([FLOOR]))
    free = level.run((0.0, 10.0, 0.0, 0, 0, 0), (1.0, -1.0, 1.0), 1.0, record=True)
    assert free.summary["impacts"] == 0 and free.summary["contact_steps"] == 0
    assert free.summary["sub_steps"] == len(free.telemetry)  # one advance per free step
    lying = DEFAULT_PEG.width / 2  # height of the centre of mass of the peg lying on the floor
    pressed = level.run((0.0, lying + 1e-3, 0.0, 0, 0, 0), (0.5, -1.0, 0.0), 1.0, record=True)
    assert pressed.summary["impacts"] >= len(pressed.telemetry) - 1
    assert pressed.summary["jams"] == 0 and pressed.summary["stalls"] == 0
