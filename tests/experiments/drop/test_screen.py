"""The screen (issue 21): a coarse-step sequential test that can only fail a design, with a
stated error. References: Wald's bounds (Wald 1945, closed forms), Monte Carlo runs of the
screen's own loop on coin flips for its exact operating characteristic, and the full
verdict at h = 1e-3 on the paper's designs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from experiments.drop.operating import (
    crossing_probability,
    design_operating_point,
    screen_fails_at_verdict_p,
    screen_operating_point,
    screened_operating_point,
)
from experiments.drop.screen import (
    PASSES,
    design_screen,
    next_entry,
    run_sequence,
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


OLD = ScreenSettings(works_p=0.95, fails_p=0.5, false_works=0.1, first_entry=0)  # issue 21's


def test_an_entry_that_always_fails_is_decided_by_three_drops_of_its_own():
    """Issue 21's test: three failures at p = 0.5 against 0.95 carry the LLR to 3 ln(0.1) =
    -6.91 < ln(0.001 / 0.9) = -6.80; two do not. The other entry drops once (the first, on
    the tie)."""
    statuses, successes, drops, faults = sequence(
        wald_of(OLD), 2, OLD.max_drops, lambda k, i: k == 0
    )
    assert screen_decision(statuses) == FAILS
    assert drops == (1, 3) and successes == (1, 0) and faults == 0


def test_by_default_four_failures_of_the_last_entry_decide_a_design_that_fails_from_it():
    """Issue 36's default: four failures against works_p = 0.85 and fails_p = 0.1 carry the
    LLR to 4 ln(0.15 / 0.9) = -7.17 <= ln(0.001 / 0.99) = -6.90, three (-5.38) do not; the
    last entry drops first, so a design that fails from it costs 4 drops, and one that fails
    from the first entry 5 (the last succeeds once, then the first fails four times)."""
    settings = ScreenSettings()
    test = wald_of(settings)
    assert 4 * math.log(0.15 / 0.9) == pytest.approx(test.llr(0, 4))
    assert test.status(0, 4) == FAILS and test.status(0, 3) == UNDECIDED
    run = run_sequence(test, 2, settings.max_drops, lambda k, i: k == 0, None, -1)
    assert (run.drops, run.successes, run.coarse_drops) == ((0, 4), (0, 0), 4)
    run = run_sequence(test, 2, settings.max_drops, lambda k, i: k == 1, None, -1)
    assert (run.drops, run.successes, run.coarse_drops) == ((4, 1), (0, 1), 5)


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
    statuses, _, drops, faults = sequence(wald_of(OLD), 2, 3, lambda k, i: next(outcomes[k]))
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
    assert screen_operating_point(0.85, settings).fails <= 2 * settings.false_fails
    assert screen_operating_point(0.0, settings).fails == pytest.approx(1.0)
    assert screen_operating_point(0.3, settings).fails > 0.9


def test_at_the_verdicts_p_093_a_design_is_failed_at_most_0002_with_a_coarse_shift_to_011():
    """Issue 36's goal, in the model of a measured shift: one entry of a design that works
    at p = 0.93 at the verdict's step loses 0.085 at the screen's (designs 181 and 214 on
    paired draws; 214's measured 0.11 too). Issue 21's test fails it with probability 0.067;
    the default at most 0.002."""
    assert screen_fails_at_verdict_p(0.93, OLD, shift=0.085) > 0.06
    for p in (0.93, 0.95, 0.97, 1.0):
        for shift in (0.085, 0.11):
            assert screen_fails_at_verdict_p(p, ScreenSettings(), shift=shift) <= 0.002


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


CONFIRMED = ScreenSettings(confirm_step=1e-3)


def test_a_coarse_failure_prunes_only_when_the_same_draws_fail_at_the_fine_step():
    """Coarse drops that always fail and fine drops of the same draws that always succeed:
    the entry is not failed; it goes on at the fine step and passes. The replay ran the
    same draw indices the coarse drops ran, failures first."""
    coarse_seen, fine_seen = [], []

    def coarse(k, i):
        coarse_seen.append((k, i))
        return False

    def fine(k, i):
        fine_seen.append((k, i))
        return True

    test = wald_of(CONFIRMED)
    run = run_sequence(test, 1, CONFIRMED.max_drops, coarse, fine)
    assert screen_decision(run.statuses) == PASSES and run.fine == (True,)
    assert coarse_seen == [(0, 0), (0, 1), (0, 2), (0, 3)]
    # the 4 coarse failures replayed newest first; then fine drops until the test passes
    assert fine_seen[:4] == [(0, 3), (0, 2), (0, 1), (0, 0)]
    assert run.drops == (len(fine_seen),) and run.successes == (len(fine_seen),)


def test_a_confirmed_failure_costs_the_replay_of_the_failed_draws_only():
    test = wald_of(CONFIRMED)
    # entry 1 (the last, first to drop) fails 4 coarse drops; their 4 replays fail too
    run = run_sequence(test, 2, 60, lambda k, i: k == 0, lambda k, i: k == 0, -1)
    assert screen_decision(run.statuses) == FAILS
    assert run.coarse_drops == 4 and run.fine_drops == 4
    # a success, then six failures (2.14 - 6 x 1.79 = -8.61; five: -6.82 > -6.90): the six
    # failures' replays decide (with the success counted a success: -8.61), it is not replayed
    outcomes = iter([True] + [False] * 6)
    run = run_sequence(test, 1, 60, lambda k, i: next(outcomes), lambda k, i: False)
    assert screen_decision(run.statuses) == FAILS and run.fine_drops == 6


def test_with_confirmation_the_error_holds_at_the_fine_p_whatever_the_coarse_step_does():
    """The worst coupling: every coarse drop fails, the fine drops succeed with p = 0.9.
    Over 20,000 screens the fraction failed is within the exact crossing probability of the
    fine walk (the bound of the module), 3.5 standard errors; without confirmation every
    screen fails."""
    p, runs = 0.9, 20_000
    bound = 1 - (1 - crossing_probability(p, CONFIRMED)) ** 1
    rng = np.random.default_rng(7)
    test = wald_of(CONFIRMED)
    fails = 0
    for _ in range(runs):

        def fine_drop(k, i, fine={}):  # noqa: B006 - one draw's fine outcome, once
            return fine.setdefault(i, rng.random() < p)

        run = run_sequence(test, 1, CONFIRMED.max_drops, lambda k, i: False, fine_drop)
        fails += screen_decision(run.statuses) == FAILS
    se = math.sqrt(bound * (1 - bound) / runs)
    assert fails / runs <= bound + 3.5 * se
    assert 0.0 < bound < 0.01
    plain = run_sequence(test, 1, CONFIRMED.max_drops, lambda k, i: False)
    assert screen_decision(plain.statuses) == FAILS


def test_the_crossing_probability_in_closed_form():
    """Within 4 drops the default test's walk reaches its lower bound only by 4 failures:
    (1 - p)^4; with no limit it is at least the test's own P(fails)."""
    four = ScreenSettings(max_drops=4)
    for p in (0.0, 0.5, 0.9):
        assert crossing_probability(p, four) == pytest.approx((1 - p) ** 4)
    assert crossing_probability(0.9, CONFIRMED) >= screen_operating_point(0.9, CONFIRMED, 1).fails


@pytest.mark.parametrize("field, value", [("first_entry", 0.5), ("confirm_step", 0.0)])
def test_bad_new_settings_name_the_field(field, value):
    with pytest.raises(ValueError, match=f"screen.{field}"):
        ScreenSettings(**{field: value})
