"""The dynamic level's one-step linearisation allowance (issue 35): derived from the contacts
the part can have in each step, each against its closed form, and the report's count of the
cases where it is vacuous."""

from __future__ import annotations

import math

import numpy as np
import pytest

from experiments.stress.bounds import VACUOUS_FRACTION, vacuous
from experiments.stress.measures import (
    Solid,
    accumulated_errors,
    linearisation_errors,
    penetration_depths,
    union_of,
)
from experiments.stress.report import summary, table
from feeders.part import Peg

FLOOR = [[-5.0, -1.0], [5.0, -1.0], [5.0, 0.0], [-5.0, 0.0]]
# a 1 x 0.5 box, its centre of mass in the middle: corners 0.559 from it
BOX = Peg(length=1.0, width=0.5, mass=1.0, com_offset=0.0, inertia=1.0 / 12.0 * 1.25)
NO_DISCS = np.zeros((0, 3))


def _arc(a: float) -> float:
    """|e^{ia} - 1 - ia|: how far a point at unit distance from the centre of a turn by a
    leaves the tangent line it is linearised on (at most a^2 / 2)."""
    return math.hypot(1.0 - math.cos(a), a - math.sin(a))


def _solid(polygons, circles=()):
    return Solid.of_union(union_of(polygons, list(circles)))


def test_a_translation_is_allowed_nothing():
    """Flat and convex gaps are linear or convex in a translation: a box sliding along the
    floor, and one sliding into it, are allowed no linearisation error."""
    states = np.array([[0.0, 0.25, 0.0], [0.3, 0.25, 0.0], [0.6, 0.2, 0.0]])
    errors = linearisation_errors(states, _solid([FLOOR]), BOX, NO_DISCS)
    assert np.all(errors == 0.0)


def test_a_part_out_of_reach_is_allowed_nothing():
    """A box turning 1 rad high above the floor: no point of it can reach the floor in the
    step (reach |dx| + R |dtheta| = 0.56 < 2), so no contact and no allowance."""
    states = np.array([[0.0, 3.0, 0.0], [0.0, 3.0, 1.0]])
    assert linearisation_errors(states, _solid([FLOOR]), BOX, NO_DISCS)[0] == 0.0


@pytest.mark.parametrize("a", [1e-3, 0.05, 0.5])
def test_a_corner_turning_on_the_floor_is_allowed_its_arc(a: float):
    """A box resting on the floor (its bottom face on it, no floor vertex within reach) turning
    by a about its centre of mass: its corners, 0.559 from it, leave their tangent lines by
    0.559 |e^{ia} - 1 - ia| (closed form); the allowance is exactly that, and the corner that
    goes down really ends no deeper (shapely's depth of the turned box, the suite's measure)."""
    lever = math.hypot(0.5, 0.25)
    states = np.array([[0.0, 0.25, 0.0], [0.0, 0.25, a]])
    solid = _solid([FLOOR])
    error = linearisation_errors(states, solid, BOX, NO_DISCS)[0]
    assert error == pytest.approx(lever * _arc(a), rel=1e-12)
    # the corner at (0.5, -0.25) turns down: its linearised gap drops by 0.5 a, its true one
    # by 0.25 - (0.25 cos a - 0.5 sin a); the difference is within the allowance
    true_depth = float(penetration_depths(solid, BOX, states[1:])[0])
    assert true_depth == pytest.approx(0.5 * math.sin(a) + 0.25 * math.cos(a) - 0.25, abs=1e-12)
    assert true_depth - 0.5 * a <= error + 1e-15


@pytest.mark.parametrize("r", [0.05, 0.3, 1.0])
def test_a_face_turning_on_a_disc_is_allowed_the_disc_centre_lever(r: float):
    """A box lying flush on top of a disc of radius r (the disc under its centre of mass),
    turning by a = 0.2: the face's gap to the disc is (0.25 + r) cos a - 0.25 - r, linearised
    0 (the contact point is under the centre of mass), so the face sinks (0.25 + r)(1 - cos a)
    into the disc. The allowance is the disc centre's lever 0.25 + r times |e^{-ia} - 1 + ia|
    (closed form, at least that depth); the box's corners are beyond the step's reach
    (0.559 a) of the disc, so their lever does not count. Reference: shapely's depth of the
    turned box."""
    a = 0.2
    disc = np.array([[0.0, -r, r]])
    solid = _solid([], disc)
    states = np.array([[0.0, 0.25, 0.0], [0.0, 0.25, a]])
    error = linearisation_errors(states, solid, BOX, disc)[0]
    centre_lever = 0.25 + r
    assert error == pytest.approx(centre_lever * _arc(a), rel=1e-9)
    sunk = centre_lever * (1.0 - math.cos(a))
    depth = float(penetration_depths(solid, BOX, states[1:])[0])
    assert depth == pytest.approx(sunk, abs=5e-6 * r + 1e-12)  # the disc is an inscribed polygon
    assert depth <= error


def test_a_small_disc_the_part_cannot_reach_adds_nothing():
    """Issue 35: the old rule took the scene's smallest disc, touched or not (d^2 / (2 r): 6.06
    allowed in one case of seed 1). A disc of radius 1e-3 four lengths away leaves the
    allowance of a box turning on the floor as it is without the disc."""
    states = np.array([[0.0, 0.25, 0.0], [0.05, 0.25, 0.3]])
    plain = linearisation_errors(states, _solid([FLOOR]), BOX, NO_DISCS)
    disc = np.array([[4.0, 1.0, 1e-3]])
    with_disc = linearisation_errors(states, _solid([FLOOR], disc), BOX, disc)
    np.testing.assert_array_equal(with_disc, plain)


def test_an_obstacle_corner_against_a_turning_face_counts_the_slide():
    """A box sliding by dx = 0.1 along its bottom face over a post's corner while turning by
    a: the face's gap to each corner leaves its linearisation by up to |u| a^2 / 2 + |dx| |a|
    (u: the corner from the centre of mass; the normal turns under the slide). The allowance
    is the exact residual |R(-a)(u - dx) - u + dx + a J u| (at most that sum), and it grows
    with the slide where a part corner's would not."""
    post = [[-0.2, -1.0], [0.2, -1.0], [0.2, 0.0], [-0.2, 0.0]]
    solid = _solid([post])
    a = 0.1
    errors = []
    for dx in (0.0, 0.1):
        states = np.array([[0.2, 0.25, 0.0], [0.2 + dx, 0.25, a]])
        errors.append(linearisation_errors(states, solid, BOX, NO_DISCS)[0])
    shift = np.array([0.1, 0.0])
    c, s = math.cos(a), math.sin(a)
    residuals = []
    for corner in ((-0.2, 0.0), (0.2, 0.0)):  # both under the box, from its centre of mass
        u = np.array(corner) - np.array([0.2, 0.25])
        w = u - shift
        back = np.array([c * w[0] + s * w[1], -s * w[0] + c * w[1]])
        residuals.append(float(np.hypot(*(back - u + shift + a * np.array([-u[1], u[0]])))))
        assert residuals[-1] <= np.hypot(*u) * a * a / 2 + 0.1 * a + 1e-12
    residual = max(residuals)
    part_corner = math.hypot(0.5, 0.25) * _arc(a)
    assert errors[1] == pytest.approx(max(residual, part_corner), rel=1e-9)
    assert errors[1] > errors[0]


def _record(index: int, h: float, step_error: float, size: float, depth: float) -> dict:
    allowed = max(0.0, 0.01) + step_error + 1e-9
    return {
        "seed": 0,
        "index": index,
        "level": "dynamic",
        "family": "convex",
        "placement": "free",
        "h": h,
        "max_depth": depth,
        "depth_allowed": allowed,
        "step_error": step_error,
        "part_size": size,
        "energy_gain": 0.0,
        "energy_allowed": 1.0,
        "crossed_step": None,
        "error": None,
        "hard": [] if depth <= allowed else ["penetration"],
        "soft": [],
    }


def test_the_report_counts_and_lists_vacuous_allowances_by_band_of_h():
    """A case is vacuous when its allowance exceeds 5 % of the part's size; the summary counts
    them per band of h (up to 2.5e-2 and above), says how many went deeper than the fixed
    tolerance (so their pass rests on the allowance), and lists each one."""
    assert VACUOUS_FRACTION == 0.05
    records = [
        _record(1, 1e-3, 1e-4, 1.0, 0.001),  # tight
        _record(2, 2e-2, 0.06, 1.0, 0.002),  # vacuous, not deeper than the tolerance
        _record(3, 5e-2, 0.5, 2.0, 0.3),  # vacuous, deeper: passes only through the allowance
        _record(4, 5e-2, 0.09, 2.0, 0.02),  # 4.5 %: not vacuous
    ]
    assert [vacuous(r) for r in records] == [False, True, True, False]
    data = summary([(r, 0.01) for r in records], 0)
    low, high = data["bands"]["h<=0.025"], data["bands"]["h>0.025"]
    assert (low["cases"], low["vacuous"], low["vacuous_deeper"]) == (2, 1, 0)
    assert (high["cases"], high["vacuous"], high["vacuous_deeper"]) == (2, 1, 1)
    assert [v["index"] for v in low["list"]] == [2] and [v["index"] for v in high["list"]] == [3]
    text = table(data)
    assert "allowance above 5% of the part's size in 1 (1 of them deeper" in text
    assert "#3 h=0.05: allowance 0.5 (part 2)" in text


def test_the_errors_add_up_while_the_part_overlaps_and_restart_once_it_is_clear():
    """An overlapping contact is only kept from approaching, so each step of an overlap may
    deepen it by that step's error: the allowance sums them from the last step begun clear
    of the solid (depth 0), and a step begun clear starts the sum again."""
    errors = np.array([1.0, 2.0, 4.0, 8.0, 16.0])
    depths = np.array([0.0, 0.1, 0.2, 0.0, 0.3, 0.0])  # at the states, before each step
    total = accumulated_errors(errors, depths)
    np.testing.assert_array_equal(total, [1.0, 3.0, 7.0, 8.0, 24.0])
