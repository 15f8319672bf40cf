"""The robust objective R (experiments.optimize.objective): success first, Eq. 10 second.

References: Eq. 10 of the paper computed by hand for hand-made trials, and the ordering the
module promises (more trials succeeding from both entries always ranks better, whatever
Eq. 10 says; at equal successes the lower mean G ranks better; a degenerate design ranks
below every buildable one)."""

import math

import pytest

from experiments.drop.verdict import UNBUILDABLE, Trial
from experiments.optimize.objective import (
    G_SCALE,
    eq10_terms,
    robust_value,
    trial_from_dict,
    trial_to_dict,
)


def trial(index, success, T=(2.0, 2.0), err=(0.1, 0.1)):
    outcome = tuple("heavy end down" if s else "heavy end up" for s in success)
    return Trial(index, tuple(success), outcome, tuple(T), tuple(err))


def test_eq10_of_one_trial_is_the_papers_sum_over_entries():
    t = trial(0, (True, False), T=(2.5, 10.0), err=(0.2, 3.0))
    assert eq10_terms(t, 5.0) == pytest.approx(5.0 * 0.2 + 2.5 + 5.0 * 3.0 + 10.0)


def test_value_is_failed_trials_plus_a_bounded_tie_break():
    trials = [trial(0, (True, True)), trial(1, (True, False)), trial(2, (False, False))]
    r = robust_value(trials, weight=5.0)
    g = 5.0 * 0.1 * 2 + 4.0
    assert r["both"] == 1 and r["successes"] == [2, 1]
    assert r["mean_g"] == pytest.approx(g)
    assert r["value"] == pytest.approx(2 + g / (g + G_SCALE))


def test_one_more_success_beats_any_eq10_value():
    slow_sure = [trial(i, (True, True), T=(9.9, 9.9), err=(1.0, 1.0)) for i in range(4)]
    fast_marginal = [trial(i, (True, True), T=(0.1, 0.1), err=(0, 0)) for i in range(3)]
    fast_marginal.append(trial(3, (True, False), T=(0.1, 0.1), err=(0, 0)))
    assert robust_value(slow_sure, 5.0)["value"] < robust_value(fast_marginal, 5.0)["value"]


def test_at_equal_successes_the_lower_mean_g_wins():
    fast = [trial(i, (True, True), T=(2.0, 2.0)) for i in range(4)]
    slow = [trial(i, (True, True), T=(3.0, 2.0)) for i in range(4)]
    assert robust_value(fast, 5.0)["value"] < robust_value(slow, 5.0)["value"]


def test_a_degenerate_design_ranks_below_every_buildable_one():
    k = 4
    worst_buildable = [trial(i, (False, False), T=(1e6, 1e6), err=(1e6, 1e6)) for i in range(k)]
    degenerate = robust_value([], 5.0, reason="the funnel walls cross", expected=k)
    assert degenerate["value"] == k + 1
    assert degenerate["reason"] == "the funnel walls cross"
    assert robust_value(worst_buildable, 5.0)["value"] < degenerate["value"]


def test_unbuildable_trials_fail_and_leave_the_mean_g():
    made = trial(0, (True, True))
    unbuilt = Trial(1, (False, False), (UNBUILDABLE,) * 2, (math.nan,) * 2, (math.nan,) * 2)
    r = robust_value([made, unbuilt], 5.0)
    assert r["both"] == 1
    assert r["mean_g"] == pytest.approx(eq10_terms(made, 5.0))


def test_trials_round_trip_through_plain_data_nan_included():
    t = Trial(3, (True, False), ("heavy end down", UNBUILDABLE), (2.0, math.nan), (0.1, math.nan))
    back = trial_from_dict(trial_to_dict(t))
    assert back.index == 3 and back.success == t.success and back.outcome == t.outcome
    assert back.T[0] == 2.0 and math.isnan(back.T[1]) and math.isnan(back.goal_error[1])
