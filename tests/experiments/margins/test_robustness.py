"""The robustness of a design is its smallest normalised room over the device's axes: checked
against acceptable regions known in closed form (the search run on a success function with
known edges), with sides at the box's edge reported and never taken as the minimum."""

from __future__ import annotations

import math

import pytest

from experiments.margins.robustness import more_robust, of_dict, robustness, room
from experiments.margins.search import RESOLUTION, Estimate, bracket

TARGET = 0.9
DROPS = 20


def row(name: str, kind: str, box: tuple[float, float], nominal: float, low: float, high: float):
    """The margins row (as :meth:`MarginsReport.to_dict` writes it) of an axis whose design
    works exactly for values in (low, high): the search run on that success function."""

    def evaluate(value: float) -> Estimate:
        return Estimate(value, DROPS if low < value < high else DROPS // 2, DROPS, DROPS)

    width = box[1] - box[0]
    sides = [bracket(evaluate, evaluate(nominal), edge, width, TARGET) for edge in box]
    return {
        "parameter": name,
        "kind": kind,
        "nominal": nominal,
        "box": list(box),
        "interval": [sides[0].limit, sides[1].limit],
        "low": sides[0].to_dict(),
        "high": sides[1].to_dict(),
    }


def margins(*rows):
    return {"works": True, "margins": list(rows)}


def test_the_smallest_room_inside_the_box_is_found_within_the_resolution():
    # fy of a feeder: box [0.5, 2.5], works for 0.76 < fy < 1.104 around 1.01: the high
    # side's room (1.104 - 1.01) / 2 = 0.047 is the closed-form robustness
    m = margins(
        row("fy", "design", (0.5, 2.5), 1.01, 0.76, 1.104),
        row("mu", "friction", (0.0, 0.3), 0.05, -1.0, 0.255),  # low side reaches mu = 0
    )
    r = robustness(m)
    exact = (1.104 - 1.01) / 2.0
    assert (r.axis, r.side) == ("fy", "high")
    assert r.bracket[0] <= exact <= r.bracket[1]
    assert r.bracket[1] - r.bracket[0] <= RESOLUTION + 1e-12
    assert r.value == r.bracket[0]
    assert "mu low" in r.edges


def test_a_side_at_the_box_edge_is_not_a_failure():
    # a chute width at its box's low edge that works over the whole box: no room is
    # measured inside the box, so it cannot be the design's weakest side
    m = margins(
        row("a", "design", (1.1, 1.2), 1.1, 0.0, 9.0),
        row("theta", "design", (0.3, 0.9), 0.4673, 0.0, 0.5071),
    )
    r = robustness(m)
    assert r.axis == "theta" and r.side == "high"
    assert set(r.edges) == {"a low", "a high", "theta low"}
    assert r.bracket[0] <= (0.5071 - 0.4673) / 0.6 <= r.bracket[1]


def test_a_design_whose_every_side_reaches_the_box_is_unlimited_within_it():
    r = robustness(margins(row("a", "design", (1.1, 1.2), 1.15, 0.0, 9.0)))
    assert r.unlimited and math.isinf(r.value)
    assert r.to_dict()["value"] is None and r.to_dict()["unlimited"]
    assert of_dict(r.to_dict()) == r


def test_part_axes_are_not_the_devices():
    m = margins(
        row("gx", "design", (0.2, 2.0), 0.733, 0.45, 0.8455),
        row("length", "part", (1.6, 2.8), 2.2, 2.19, 2.523),  # tight, but the part's
    )
    assert robustness(m).axis == "gx"
    assert robustness(m, kinds=("design", "part")).axis == "length"


def test_an_axis_without_a_margin_or_a_design_that_fails_has_no_robustness():
    m = margins(row("gx", "design", (0.2, 2.0), 0.733, 0.45, 0.8455))
    m["margins"].append({"parameter": "fy", "kind": "design", "interval": None, "box": [0, 1]})
    assert robustness(m).value == 0.0 and robustness(m).none == ("fy",)
    assert robustness({"works": False, "margins": []}).value == 0.0


def test_two_designs_are_told_apart_only_beyond_the_resolution():
    tight = robustness(margins(row("fy", "design", (0.5, 2.5), 1.0, 0.5, 1.016)))
    wide = robustness(margins(row("fy", "design", (0.5, 2.5), 1.0, 0.5, 1.2)))
    near = robustness(margins(row("fy", "design", (0.5, 2.5), 1.0, 0.5, 1.018)))
    assert more_robust(wide, tight) and not more_robust(tight, wide)
    assert not more_robust(near, tight) and not more_robust(tight, near)


def test_room_is_measured_in_fractions_of_the_box():
    r = room({"interval": [0.75, 1.1], "box": [0.5, 2.5], "nominal": 1.0})
    assert r == pytest.approx((0.125, 0.05))


def _side(row_name: str, nominal: float, box: list[float], inside: float, outside: float):
    return {
        "parameter": row_name,
        "kind": "design",
        "nominal": nominal,
        "box": box,
        "interval": [inside, box[1]],
        "low": {"at_box_edge": False, "first_outside": {"value": outside}},
        "high": {"at_box_edge": True, "first_outside": None},
    }


def test_brackets_that_touch_are_a_tie():
    # found in a default run (seed 0): design 34's gx low room 0.0625 (+3e-17 of rounding)
    # against table3's gy low bracket ending at 0.0625 was called "more robust"; brackets
    # that only touch are one resolution step apart, a tie
    design = robustness(
        margins(_side("gx", 0.9988706300471999, [0.2, 2.0], 0.8863706300471998, 0.87230813))
    )
    table3 = robustness(
        margins(_side("gy", 2.0388, [1.5, 3.0], 1.9567687500000002, 1.9450500000000002))
    )
    assert abs(design.bracket[0] - table3.bracket[1]) < 1e-12
    assert not more_robust(design, table3) and not more_robust(table3, design)
