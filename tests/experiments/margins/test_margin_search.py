"""The bracketing search finds a known threshold of a synthetic success function to its
stated resolution, and never evaluates outside the box."""

from __future__ import annotations

import math

import pytest

from experiments.margins.search import RESOLUTION, Estimate, bracket

TARGET = 0.9
DROPS = 20


def synthetic(threshold_low: float, threshold_high: float, seen: list[float]):
    """P(both) = 1 strictly between the thresholds, 0.5 outside: a monotone success function
    with known edges (the injected estimator)."""

    def evaluate(value: float) -> Estimate:
        seen.append(value)
        p = 1.0 if threshold_low < value < threshold_high else 0.5
        return Estimate(value, round(p * DROPS), DROPS, DROPS)

    return evaluate


@pytest.mark.parametrize("threshold", [0.3001, 0.37, 0.52, 0.8, 0.999])
def test_search_finds_the_threshold_to_the_resolution(threshold):
    seen: list[float] = []
    evaluate = synthetic(-math.inf, threshold, seen)
    nominal = evaluate(0.3)
    side = bracket(evaluate, nominal, edge=1.0, width=1.0, target=TARGET)
    assert not side.at_edge
    assert side.limit < threshold <= side.outside.value
    assert side.outside.value - side.limit <= RESOLUTION
    assert len(side.evaluations) <= 12  # doubling then bisection, not a scan


def test_search_downward_finds_the_lower_threshold():
    seen: list[float] = []
    evaluate = synthetic(2.137, math.inf, seen)
    side = bracket(evaluate, evaluate(3.0), edge=2.0, width=1.0, target=TARGET)
    assert side.outside.value <= 2.137 < side.limit
    assert side.limit - side.outside.value <= RESOLUTION


def test_a_margin_reaching_the_box_edge_stops_there_and_says_so():
    seen: list[float] = []
    evaluate = synthetic(-math.inf, 5.0, seen)  # works beyond the box
    side = bracket(evaluate, evaluate(0.2), edge=1.0, width=1.0, target=TARGET)
    assert side.at_edge and side.limit == 1.0 and side.outside is None
    assert max(seen) == 1.0


@pytest.mark.parametrize("threshold", [0.05, 0.41, 0.77, 0.999, 3.0])
def test_a_margin_never_leaves_the_box(threshold):
    seen: list[float] = []
    evaluate = synthetic(-threshold, threshold, seen)
    nominal = evaluate(0.0)
    low = bracket(evaluate, nominal, edge=-1.0, width=2.0, target=TARGET)
    high = bracket(evaluate, nominal, edge=1.0, width=2.0, target=TARGET)
    assert all(-1.0 <= v <= 1.0 for v in seen)
    assert -1.0 <= low.limit <= 0.0 <= high.limit <= 1.0


def test_a_nominal_at_the_edge_has_no_room_on_that_side():
    seen: list[float] = []
    evaluate = synthetic(-math.inf, math.inf, seen)
    nominal = evaluate(1.1)
    side = bracket(evaluate, nominal, edge=1.1, width=0.1, target=TARGET)
    assert side.at_edge and side.limit == 1.1 and side.evaluations == ()


def test_the_search_refuses_a_nominal_below_the_target():
    with pytest.raises(ValueError, match="not inside"):
        bracket(lambda v: Estimate(v, 0, DROPS, DROPS), Estimate(0.0, 10, DROPS, DROPS), 1.0,
                1.0, TARGET)  # fmt: skip


def test_an_estimate_stopped_early_is_outside_and_the_count_rule_is_the_targets():
    assert Estimate(0.0, 18, 20, 20).inside(0.9)
    assert not Estimate(0.0, 17, 20, 20).inside(0.9)
    assert not Estimate(0.0, 1, 4, 20).inside(0.9)  # stopped: 3 failures > the 2 allowed
