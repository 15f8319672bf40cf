"""The screen (issue 21): a coarse-step sequential test that can only fail a design, with a
stated error. References: Wald's bounds (Wald 1945, closed forms), Monte Carlo runs of the
screen's own loop on coin flips for its exact operating characteristic, and the full
verdict at h = 1e-3 on the paper's designs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from experiments.drop.operating import (
    design_operating_point,
    screen_operating_point,
    screened_operating_point,
)
from experiments.drop.screen import (
    PASSES,
    design_screen,
    next_entry,
    screen_decision,
    sequence,
    wald_of,
)
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.sequential import FAILS, UNDECIDED, WORKS, Wald
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import PRESETS


def test_wald_bounds_are_walds_closed_forms():
    symmetric = Wald(0.95, 0.8, 0.01)
    assert symmetric.upper == pytest.approx(math.log(99.0))
    assert symmetric.lower == pytest.approx(-math.log(99.0))
    screen = Wald(0.95, 0.5, false_works=0.1, false_fails=0.001)
    assert screen.upper == pytest.approx(math.log(0.999 / 0.1))
    assert screen.lower == pytest.approx(math.log(0.001 / 0.9))


def test_an_entry_that_always_fails_is_decided_by_three_drops_of_its_own():
    """Three failures at p = 0.5 against 0.95 carry the LLR to 3 ln(0.1) = -6.91 < ln(0.001 /
    0.9) = -6.80; two do not. The other entry drops once (the first, on the tie)."""
    settings = ScreenSettings()
    statuses, successes, drops, faults = sequence(
        wald_of(settings), 2, settings.max_drops, lambda k, i: k == 0
    )
    assert screen_decision(statuses) == FAILS
    assert drops == (1, 3) and successes == (1, 0) and faults == 0


def test_the_next_drop_is_from_the_entry_most_likely_to_fail():
    test = Wald(0.95, 0.5, false_works=0.1, false_fails=0.001)
    assert next_entry(test, [UNDECIDED, UNDECIDED], [0, 0], [0, 0]) == 0  # tie: the first
    assert next_entry(test, [UNDECIDED, UNDECIDED], [3, 2], [3, 3]) == 1
    assert next_entry(test, [WORKS, UNDECIDED], [30, 20], [30, 20]) == 1  # decided: not again
    assert next_entry(test, [UNDECIDED, UNDECIDED], [0, 2], [3, 2], max_drops=3) == 1
    assert next_entry(test, [UNDECIDED, WORKS], [0, 2], [3, 2], max_drops=3) is None


def test_each_entry_is_tested_to_its_own_max_drops_as_the_characteristic_assumes():
    """Entry 0 stays undecided through its 3 drops (F, S, S: LLR -1.02); entry 1, which fails
    every drop, is then still tested, to its own 3, and fails the design. (The loop once
    stopped when any entry reached max_drops, leaving the design undecided; the exact
    operating characteristic truncates each entry's test at its own max_drops.)"""
    outcomes = {0: iter([False, True, True]), 1: iter([False] * 3)}
    statuses, _, drops, faults = sequence(
        wald_of(ScreenSettings()), 2, 3, lambda k, i: next(outcomes[k])
    )
    assert statuses == (UNDECIDED, FAILS) and drops == (3, 3) and faults == 0
    assert screen_decision(statuses) == FAILS


def test_faults_are_drawn_again_and_not_counted():
    settings = ScreenSettings()
    outcomes = iter([None, None, True, None, True] + [True] * 100)
    statuses, successes, drops, faults = sequence(
        wald_of(settings), 2, settings.max_drops, lambda k, i: next(outcomes)
    )
    assert faults == 3
    assert screen_decision(statuses) == PASSES
    assert sum(drops) == sum(successes)


@pytest.mark.parametrize("p", [0.6, 0.8, 0.9, 0.95])
def test_operating_characteristic_matches_the_loop_on_coin_flips(p):
    """The exact P(fails) and P(passes) of a design whose two entries succeed with p, against
    4,000 runs of the screen's own loop (3.5 standard errors)."""
    settings = ScreenSettings()
    exact = screen_operating_point(p, settings)
    rng = np.random.default_rng(42)
    runs = 4000
    decisions = [
        screen_decision(
            sequence(wald_of(settings), 2, settings.max_drops, lambda k, i: rng.random() < p)[0]
        )
        for _ in range(runs)
    ]
    for decision, probability in ((FAILS, exact.fails), (PASSES, exact.passes)):
        measured = decisions.count(decision) / runs
        se = math.sqrt(max(probability * (1 - probability), 1e-4) / runs)
        assert abs(measured - probability) < 3.5 * se, (decision, measured, probability)


def test_the_stated_error_holds_a_design_that_works_is_almost_never_failed():
    settings = ScreenSettings()
    assert screen_operating_point(0.95, settings).fails <= 2 * settings.false_fails
    assert screen_operating_point(0.0, settings).fails == pytest.approx(1.0)
    assert screen_operating_point(0.3, settings).fails > 0.999


def test_screen_then_verdict_is_the_product_of_the_two():
    screen, verdict = ScreenSettings(), VerdictSettings(rule="sprt", min_drops=1, batch=1)
    for p in (0.8, 0.95):
        whole = screened_operating_point(p, screen, verdict)
        first = screen_operating_point(p, screen)
        then = design_operating_point(p, verdict)
        assert whole.works == pytest.approx((1 - first.fails) * then.works)
        assert whole.works + whole.fails + whole.undecided == pytest.approx(1.0)
    assert screened_operating_point(0.95, screen, verdict).works > 0.98


def test_a_design_that_works_passes_and_one_that_fails_is_failed():
    """table3 works (the verdict: 40 of 40 from both entries); fig5b fails from one entry
    (docs/calibration.md). Same seed, same screen."""
    for seed in (1, 2, 3):
        assert design_screen(PRESETS["table3"], seed=seed).decision == PASSES
    failed = design_screen(PRESETS["fig5b"], seed=1)
    assert failed.decision == FAILS
    assert failed.total_drops <= 10
    again = design_screen(PRESETS["fig5b"], seed=1)
    assert (again.drops, again.successes, again.statuses) == (
        failed.drops,
        failed.successes,
        failed.statuses,
    )


@pytest.mark.parametrize(
    "field, value",
    [("false_fails", 0.0), ("fails_p", 0.97), ("max_drops", 2.5), ("step", float("nan"))],
)
def test_bad_settings_name_the_field(field, value):
    with pytest.raises(ValueError, match=f"screen.{field}"):
        ScreenSettings(**{field: value})
