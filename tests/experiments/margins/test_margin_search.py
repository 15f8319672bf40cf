"""The bracketing search finds a known threshold of a synthetic success function to its
stated resolution, and never evaluates outside the box; on looks (issue 34) it reports ends
that meet the full rule, recovers from a look the full rule contradicts, looks at the box's
edge first without hiding a failing band before it, and costs a stated number of trials."""

from __future__ import annotations

import hashlib
import math

import numpy as np
import pytest

from experiments.margins.search import (
    RESOLUTION,
    Estimate,
    NominalFailed,
    Sampler,
    bracket,
    nominal_estimate,
    required,
    search,
)

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


# The search on looks (issue 34): values passed on a trial or two, the ends by the full rule.
# Synthetic trials: ``outcome(value, index)`` is trial ``index`` at ``value`` (None: a fault).


def thresholds_outcome(thresholds, seen=None):
    """Trial i succeeds below its own threshold and fails from it on: a success step in the
    value per trial, as common random numbers nearly make it (the upper side)."""

    def outcome(value: float, index: int) -> bool | None:
        if seen is not None:
            seen.append((value, index))
        return value < thresholds[index % len(thresholds)]

    return outcome


def noisy_outcome(p, seed=0):
    """Trial i at a value succeeds with probability p(value), independently of every other
    (value, trial): no single crossing of the full rule's answers is promised."""

    def outcome(value: float, index: int) -> bool | None:
        key = f"{seed}:{value!r}:{index}".encode()
        u = int.from_bytes(hashlib.sha256(key).digest()[:8], "big") / 2**64
        return u < p(value)

    return outcome


def side(outcome, nominal=0.0, edge=1.0, width=1.0, drops=DROPS, target=TARGET):
    trials = Sampler(outcome, drops, target)
    assert nominal_estimate(trials, nominal).inside(target)
    return search(trials, nominal, edge, width), trials


def full_estimates(outcome, drops=DROPS, target=TARGET):
    """The estimator of the search on full estimates: each value's first ``drops`` counted
    trials in draw order, stopped at the first failure past the allowance."""

    def evaluate(value: float) -> Estimate:
        s = f = index = 0
        while s + f < drops and index < 2 * drops and f <= drops - required(target, drops):
            result = outcome(value, index)
            index += 1
            if result is not None:
                s, f = s + result, f + (not result)
        return Estimate(value, s, s + f, drops)

    return evaluate


def assert_the_rule(result, nominal, target=TARGET, drops=DROPS):
    """The reported last inside has all ``drops`` trials counted and enough successes; the
    first outside failed the rule; they are within the resolution; every value estimated
    lies between the nominal and the edge."""
    inside = result.inside
    assert inside.drops == inside.planned == drops
    assert inside.successes >= required(target, drops) and inside.inside(target)
    if result.outside is None:
        assert result.limit == result.edge
    else:
        assert result.outside.planned == drops and result.outside.failed(target)
        assert abs(result.outside.value - result.limit) <= result.resolution + 1e-12
    lo, hi = sorted((nominal, result.edge))
    assert all(lo <= e.value <= hi for e in result.evaluations)


CURVES = {
    "sharp at 0.3": lambda v: 1.0 if v < 0.3 else 0.0,
    "soft around 0.55": lambda v: min(1.0, max(0.0, 1.0 - (v - 0.4) * 1.2)),
    "a dip at 0.2 then recovery": lambda v: 0.8 if 0.18 < v < 0.22 else 1.0 - 0.9 * v,
    "works everywhere": lambda v: 1.0,
}


@pytest.mark.parametrize("curve", sorted(CURVES))
@pytest.mark.parametrize("seed", range(6))
def test_every_end_reported_has_the_full_rule_on_any_trials(curve, seed):
    outcome = noisy_outcome(CURVES[curve], seed)
    result, _ = side(outcome)
    assert_the_rule(result, 0.0)


@pytest.mark.parametrize("spread", [0.0, 0.02, 0.1, 0.3])
def test_per_trial_thresholds_give_the_third_lowest_as_the_end(spread):
    """With a step per trial, the full rule's answer crosses once, at the third lowest
    threshold of the 20 (two failures allowed): the search brackets it to the resolution
    and ends where the search on full estimates ends."""
    rng = np.random.default_rng(7)
    thresholds = 0.45 + spread * rng.random(DROPS)
    outcome = thresholds_outcome(thresholds)
    result, _ = side(outcome)
    crossing = np.sort(thresholds)[2]
    assert result.limit < crossing <= result.outside.value
    assert_the_rule(result, 0.0)
    evaluate = full_estimates(outcome)
    full = bracket(evaluate, evaluate(0.0), 1.0, 1.0, TARGET)
    assert (result.limit, result.outside.value) == (full.limit, full.outside.value)
    assert result.drops < full.drops / 2


def test_a_tentative_acceptance_the_full_rule_contradicts_is_recovered():
    """From 0.3 to 0.7 three trials (15, 16, 17) fail and the rest succeed: a look there,
    led by trial 0 (the first to fail at the edge), passes, so 0.5 (a doubling step) and
    values beyond it are accepted tentatively; their confirmation fails, and the search
    goes back and ends at 0.3, where the search on full estimates ends."""

    def outcome(value: float, index: int) -> bool:
        if value < 0.3:
            return True
        if value < 0.7:
            return index not in (15, 16, 17)
        return False

    result, trials = side(outcome)
    assert_the_rule(result, 0.0)
    evaluate = full_estimates(outcome)
    full = bracket(evaluate, evaluate(0.0), 1.0, 1.0, TARGET)
    assert (result.limit, result.outside.value) == (full.limit, full.outside.value)
    assert result.limit < 0.3 <= result.outside.value
    looked = {e.value: e for e in result.evaluations}
    assert 0.5 in looked and looked[0.5].failed(TARGET)  # accepted on a look, then failed
    assert trials.made_at(0.5)[0] is True  # ... the look's trial
    assert any(0.5 < v < 0.7 and e.failed(TARGET) for v, e in looked.items())


def test_a_side_whose_edge_is_inside_is_done_at_the_edge_after_a_scan():
    """The edge is looked at first and, inside, confirmed: 20 trials; then one trial at
    each doubling step the search on full estimates would have judged (1/32 ... 1/2 of the
    box): 25 trials in all, where the search on full estimates made 6 x 20."""
    seen: list[tuple[float, int]] = []
    outcome = thresholds_outcome([5.0] * DROPS, seen)
    result, _ = side(outcome)
    assert result.at_edge and result.limit == 1.0
    assert result.evaluations[0].value == 1.0 and result.inside.drops == DROPS
    assert [e.value for e in result.evaluations[1:]] == [1 / 32, 1 / 16, 1 / 8, 1 / 4, 1 / 2]
    assert result.drops == 25
    evaluate = full_estimates(outcome)
    assert bracket(evaluate, evaluate(0.0), 1.0, 1.0, TARGET).drops == 6 * DROPS


def test_a_failing_band_before_an_inside_edge_is_not_hidden_by_the_edge():
    """Everything works but a band from 0.4 to 0.6 (no single crossing): the edge is inside,
    and the scan's look at 0.5 (a doubling step) fails, so the side ends below the band, as
    the search on full estimates ends, not at the edge."""

    def outcome(value: float, index: int) -> bool:
        return not 0.4 <= value < 0.6

    result, _ = side(outcome)
    assert not result.at_edge and result.limit < 0.4 <= result.outside.value
    assert_the_rule(result, 0.0)
    evaluate = full_estimates(outcome)
    full = bracket(evaluate, evaluate(0.0), 1.0, 1.0, TARGET)
    assert (result.limit, result.outside.value) == (full.limit, full.outside.value)


def test_the_drops_of_a_sharp_end():
    """Every trial fails from 0.3 on. The edge's look (1 failure); the doubling steps 1/32,
    1/16, 1/8, 1/4 (1 success each) and 1/2 (1 failure); bisection 0.375, 0.3125 (1 failure
    each), 0.28125 (1 success), then, the bracket within 4 resolution steps, 0.296875 (2
    successes) and 0.3046875 (1 failure); the full rule at 0.3046875 (2 failures more) and
    at 0.296875 (18 successes more): 32 trials, where the search on full estimates makes
    135 (a value inside costs it 20; the edge 3, the other values outside 3 each)."""
    outcome = thresholds_outcome([0.3] * DROPS)
    result, _ = side(outcome)
    assert (result.limit, result.outside.value) == (0.296875, 0.3046875)
    made = {e.value: e.drops for e in result.evaluations}
    assert made == {1.0: 1, 1 / 32: 1, 1 / 16: 1, 1 / 8: 1, 1 / 4: 1, 1 / 2: 1, 0.375: 1,
                    0.3125: 1, 0.28125: 1, 0.296875: 20, 0.3046875: 3}  # fmt: skip
    assert result.drops == 32
    evaluate = full_estimates(outcome)
    assert bracket(evaluate, evaluate(0.0), 1.0, 1.0, TARGET).drops == 135


def test_the_search_is_deterministic():
    """The same trials give the same side, made in the same order, whatever ran before."""
    runs = []
    for _ in range(2):
        seen: list[tuple[float, int]] = []
        rng = np.random.default_rng(3)
        outcome = thresholds_outcome(0.5 + 0.2 * rng.random(DROPS), seen)
        result, _ = side(outcome, nominal=0.1, edge=0.9, width=0.8)
        runs.append((result, seen))
    assert runs[0] == runs[1]


def test_a_trial_faulting_is_left_out_and_the_next_draw_counted():
    """Faults (None) at some draws: the end still counts 20 trials, the first 20 that did
    not fault in draw order (no look ever uses a draw past them)."""
    faults = {2, 5, 11}

    def outcome(value: float, index: int) -> bool | None:
        return None if index in faults else value < 0.4

    result, trials = side(outcome)
    assert_the_rule(result, 0.0)
    made = trials.made_at(result.limit)
    counted = sorted(i for i, r in made.items() if r is not None)
    assert counted == [i for i in range(DROPS + len(faults)) if i not in faults]


def test_a_side_that_comes_back_to_a_failing_nominal_says_so():
    """The nominal passes its look (draw 0) but fails the full rule, and so does every value
    beyond: the search comes back to it and raises, with the nominal's full estimate."""

    def outcome(value: float, index: int) -> bool:
        return index == 0 or index > 10

    trials = Sampler(outcome, DROPS, TARGET)
    assert nominal_estimate(trials, 0.0) == Estimate(0.0, 1, 1, 1)
    with pytest.raises(NominalFailed) as failed:
        search(trials, 0.0, 1.0, 1.0)
    assert failed.value.estimate.value == 0.0 and failed.value.estimate.failed(TARGET)


def test_a_nominal_whose_look_fails_gets_the_full_rule():
    one_failure = Sampler(lambda v, i: i != 0, DROPS, TARGET)
    e = nominal_estimate(one_failure, 0.0)
    assert (e.successes, e.drops, e.planned) == (19, 20, 20) and e.inside(TARGET)
    three = Sampler(lambda v, i: i > 2, DROPS, TARGET)
    e = nominal_estimate(three, 0.0)
    assert e.failed(TARGET) and e.drops == 3


def doubling_then_bisection(evaluate, nominal, edge, width, target=TARGET):
    """The search before issue 34, as it was: from the nominal, steps of 1/32 of the box
    doubling (clipped to the edge) until a value is outside or the edge inside, then
    bisection to 1/128 of the box, every value by its full estimate. Its ends."""
    span, sign = abs(edge - nominal.value), 1.0 if edge >= nominal.value else -1.0
    inside, outside, step = nominal, None, width / 32
    while span > 0.0:
        value = edge if step >= span else nominal.value + sign * step
        e = evaluate(value)
        if not e.inside(target):
            outside = e
            break
        inside = e
        if value == edge:
            break
        step *= 2.0
    while outside is not None and abs(outside.value - inside.value) > width / 128:
        e = evaluate(0.5 * (inside.value + outside.value))
        inside, outside = (e, outside) if e.inside(target) else (inside, e)
    return inside.value, None if outside is None else outside.value


@pytest.mark.parametrize("curve", sorted(CURVES))
@pytest.mark.parametrize("seed", range(6))
def test_on_full_estimates_the_ends_are_those_of_the_search_before(curve, seed):
    """Every value judged by its full estimate, the edge first changes no end: an inside
    edge is reported only once every doubling step has been found inside, as before."""
    evaluate = full_estimates(noisy_outcome(CURVES[curve], seed))
    nominal = evaluate(0.0)
    result = bracket(evaluate, nominal, 1.0, 1.0, TARGET)
    outside = None if result.outside is None else result.outside.value
    assert (result.limit, outside) == doubling_then_bisection(evaluate, nominal, 1.0, 1.0)


def test_a_look_of_no_trial_is_refused():
    trials = Sampler(lambda v, i: True, DROPS, TARGET)
    with pytest.raises(ValueError, match="at least one"):
        nominal_estimate(trials, 0.0, look=0)
    with pytest.raises(ValueError, match="at least one"):
        search(trials, 0.0, 1.0, 1.0, look=0)
