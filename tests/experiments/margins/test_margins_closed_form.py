"""A design's margins and robustness against a margin known in closed form (issue 34).

The reference is geometry, not the code under test: ``data/pit.yaml`` is a vertical chute
1.0 wide closed by a floor whose top lies ``depth`` below the goal's top (y = 0), and the
default peg (length L = 2.2, width w = 0.7, heavy half's share h = 0.9) dropped upright,
heavy end down. A drop ends when the part's centre of mass falls below the goal's top, or
when the part comes to rest. The part comes to rest standing on its heavy end, so its centre
of mass rests

    d* = L/2 - (h - 1/2) L/2 = 0.66

above the floor: the heavy end's distance to the centre of mass of two uniform halves, whose
centre of mass lies (h - 1/2) L/2 from the middle.

It does not rest tilted. A peg standing on a corner at tilt t has its centre of mass
d* cos t + (w/2) sin t above the floor, which is more than d* while
t < 2 atan((w/2) / d*). Its centre of mass lies over the corner's inner side while
t < atan((w/2) / d*) = 0.49 rad, so it tips back onto its end. The chute allows at most the
tilt t_max with w cos t_max + L sin t_max = 1.0, which is 0.14 rad.

So a drop succeeds if and only if depth > d*. That holds from either entry and for any
perturbation of the start or of mu: every trial's threshold is the same, and P(both) steps
from 1 to 0 at d*. With every other axis at nominal:

- the margin of ``depth`` is [d*, the box's high edge];
- the margin of mu is the whole of its box;
- the design's robustness (:func:`experiments.margins.robustness.robustness`) is
  (nominal - d*) / (the box's width), limited by depth's low side.

The band the measured low end must fall in is the search's resolution (the last value inside
and the first outside are at most ``resolution`` of the box apart, and they straddle the
crossing) plus ``CONTACT``. ``CONTACT`` is how far the simulated crossing may lie from d*:
the floor's contact is solved at the velocity level, so a resting part's gap is 0. Unperturbed
drops fail at depth 0.6599 and succeed at 0.6601. ``CONTACT`` is 1e-3, ten times that.

Nothing here depends on how the search is run (its steps, looks or drop counts): only on
its last value inside and first outside, each estimated on the same draws at its value.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

from experiments.drop.passive import passive_drop
from experiments.margins.measure import FamilySubject, MarginSettings
from experiments.margins.robustness import robustness
from experiments.margins.run import MarginsReport, margins_of
from feeders.device_family import load_family

FIXTURE = Path(__file__).with_name("data") / "pit.yaml"
SPEC = yaml.safe_load(FIXTURE.read_text())
PART = SPEC["part"]
L, W, H = PART["length"], PART["width"], PART["heavy_fraction"]
CHUTE = SPEC["pieces"][1]["polygon"][0][0] - SPEC["pieces"][0]["polygon"][1][0]
DEPTH = SPEC["parameters"]["depth"]
BOX = (DEPTH["low"], DEPTH["high"])
BOX_WIDTH = BOX[1] - BOX[0]

D_STAR = L / 2 - (H - 0.5) * L / 2  # heavy end to the centre of mass: the resting height
CONTACT = 1e-3  # the simulated crossing's distance from D_STAR we allow (see the module)
SETTINGS = MarginSettings(drops=10, seed=11, t_max=2.0)  # a drop ends within 0.7 s


def _tilt_max() -> float:
    """The largest tilt (rad) of the peg in the chute: w cos t + L sin t = CHUTE."""
    r = math.hypot(W, L)
    return math.asin(CHUTE / r) - math.atan2(W, L)


def test_the_reference_is_the_geometry_of_the_fixture():
    assert (L, W, H) == (2.2, 0.7, 0.9) and CHUTE == 1.0 and BOX == (0.3, 1.3)
    assert D_STAR == pytest.approx(0.66)
    tilt = _tilt_max()
    assert W * math.cos(tilt) + L * math.sin(tilt) == pytest.approx(CHUTE)
    assert tilt == pytest.approx(0.140, abs=1e-3)
    # a peg standing on a corner within the chute's tilt tips back onto its heavy end
    assert tilt < math.atan((W / 2) / D_STAR)
    assert BOX[0] < D_STAR < DEPTH["default"] <= BOX[1]


@pytest.mark.parametrize("entry", ["low_start", "high_start"])
def test_an_unperturbed_drop_succeeds_iff_the_floor_lies_deeper_than_the_resting_height(entry):
    family = load_family(FIXTURE)
    deeper = passive_drop(family.build([D_STAR + CONTACT]), entry, t_max=SETTINGS.t_max)
    shallower = passive_drop(family.build([D_STAR - CONTACT]), entry, t_max=SETTINGS.t_max)
    assert (deeper.success, deeper.end) == (True, "crossed")
    assert (shallower.success, shallower.end) == (False, "at_rest")
    # at rest on its heavy end, its centre of mass d* above the floor at -(d* - CONTACT)
    assert shallower.final_pose[1] == pytest.approx(CONTACT, abs=1e-4)
    assert shallower.final_pose[2] == pytest.approx(-math.pi / 2, abs=1e-4)


@pytest.fixture(scope="module", params=[DEPTH["default"], 0.8], ids=lambda d: f"depth={d}")
def report(request) -> MarginsReport:
    """The margins of the design at ``depth`` (10 trials a value, seed 11, drops of at most
    2 s): one run per nominal, shared by the tests below."""
    family = load_family(FIXTURE)
    subject = FamilySubject.of_family(family, FIXTURE.read_text(), [request.param])
    return margins_of(subject, SETTINGS)


def _row(report: MarginsReport, name: str) -> dict:
    (row,) = [r for r in report.to_dict()["margins"] if r["parameter"] == name]
    return row


def _resolution(report: MarginsReport) -> float:
    """The search's resolution on depth's axis (a length): 1/128 of the box."""
    return report.to_dict()["search"]["resolution"] * BOX_WIDTH


def test_depths_low_end_is_the_resting_height_of_the_centre_of_mass(report):
    """The design works, and its margin along depth runs from d* (the floor at which the
    resting centre of mass reaches the goal's top) to the box's high edge. The low end lies
    within the band [d* - CONTACT, d* + resolution + CONTACT]. The first value found outside
    lies within the band [d* - resolution - CONTACT, d* + CONTACT]."""
    assert report.verdict.works
    row = _row(report, "depth")
    res = _resolution(report)
    assert res == pytest.approx(BOX_WIDTH / 128)
    low, high = row["low"], row["high"]
    assert not low["at_box_edge"]
    inside, outside = low["last_inside"], low["first_outside"]
    assert row["interval"][0] == inside["value"]
    assert D_STAR - CONTACT <= inside["value"] <= D_STAR + res + CONTACT
    assert D_STAR - res - CONTACT <= outside["value"] <= D_STAR + CONTACT
    assert 0 < inside["value"] - outside["value"] <= res + 1e-12
    # P(both) is a step at d*: away from it every trial succeeds above and fails below
    if inside["value"] > D_STAR + CONTACT:
        assert inside["successes"] == inside["drops"] == SETTINGS.drops
    if outside["value"] < D_STAR - CONTACT:
        assert outside["successes"] == 0
    # every depth above the nominal lets the part through: the high side is the box's edge
    assert high["at_box_edge"] and row["interval"][1] == BOX[1]


def test_mu_does_not_matter_its_margin_is_its_whole_box(report):
    row = _row(report, "mu")
    assert row["low"]["at_box_edge"] and row["high"]["at_box_edge"]
    assert row["interval"] == row["box"]


def test_robustness_is_the_closed_form_room_below_the_nominal_depth(report):
    """robustness = (nominal - d*) / box width, within the low end's band, limited by depth's
    low side; the sides at the box's edge (depth high, mu both) are reported, never taken."""
    nominal = _row(report, "depth")["nominal"]
    exact = (nominal - D_STAR) / BOX_WIDTH
    res, tol = _resolution(report) / BOX_WIDTH, CONTACT / BOX_WIDTH
    r = robustness(report.to_dict())
    assert (r.axis, r.side) == ("depth", "low")
    assert exact - res - tol <= r.value <= exact + tol
    assert r.bracket[0] == r.value
    assert r.bracket[0] - tol <= exact <= r.bracket[1] + tol  # the bracket holds the truth
    assert r.bracket[1] - r.bracket[0] <= res + 1e-12
    assert set(r.edges) == {"depth high", "mu low", "mu high"} and r.none == ()
    assert not r.unlimited
