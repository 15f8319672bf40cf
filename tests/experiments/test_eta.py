"""The time left of a job whose items cost unequal amounts (issue 39: a sweep's terminal read
"00:02" for 87 s, then "03:22": the designs stopped at the cheap first rung finish first).
Specified on synthetic sequences of job costs run through a simulated first-in first-out
worker pool whose clock is the sum of the costs it ran (counts and costs, no wall clock); the
truth each estimate is judged against is the time the simulation still took."""

from __future__ import annotations

import heapq
from collections import deque

import pytest

from experiments.eta import Eta, LadderEta, clock_text, rate_eta

COSTS = (1.0, 5.0, 20.0)  # s per job at each stage: rising, as the ladder's levels do


def climbs(item: int, stage: int) -> bool:
    """Half the items go on from stage 0, half of those from stage 1: 10 -> 5 -> 3 jobs."""
    return item % (2 ** (stage + 1)) == 0


def simulate(items: int, workers: int) -> list[dict]:
    """Every completion of a sweep-like run: jobs queued first in, first out (a design's next
    stage is queued when its result comes, as the ladder does), ``workers`` at a time. Each
    snapshot holds the clock, the estimate, tqdm's rate over finished items, and the truth."""
    eta = LadderEta(len(COSTS), [0] * items)
    queue = deque((item, 0) for item in range(items))
    running: list[tuple[float, int, int]] = []
    now, finished, snapshots = 0.0, 0, []
    while queue or running:
        while queue and len(running) < workers:
            item, stage = queue.popleft()
            heapq.heappush(running, (now + COSTS[stage], item, stage))
        now, item, stage = heapq.heappop(running)
        goes_on = stage + 1 < len(COSTS) and climbs(item, stage)
        eta.result(stage, COSTS[stage], goes_on)
        if goes_on:
            queue.append((item, stage + 1))
        else:
            finished += 1
        snapshots.append(
            {
                "now": now,
                "stage": stage,
                "eta": eta.eta(now),
                "rate": rate_eta(now, finished, items - finished),
            }
        )
    for snapshot in snapshots:
        snapshot["truth"] = now - snapshot["now"]
    return snapshots


def test_an_eta_is_marked_a_lower_bound_while_a_stage_with_work_is_unmeasured_and_is_one():
    snapshots = simulate(items=10, workers=1)
    marked = [s for s in snapshots if s["eta"].at_least]
    assert marked  # the first stage's results come before any other's
    for s in marked:
        assert s["eta"].seconds <= s["truth"] + 1e-9
    first_top = next(k for k, s in enumerate(snapshots) if s["stage"] == len(COSTS) - 1)
    assert all(not s["eta"].at_least for s in snapshots[first_top:])
    assert all(s["eta"].at_least for s in snapshots[:first_top])


def test_once_every_stage_has_reported_the_estimate_is_the_expected_work_left():
    snapshots = simulate(items=10, workers=1)
    first_top = next(k for k, s in enumerate(snapshots) if s["stage"] == len(COSTS) - 1)
    # every stage measured at its true cost and pass fraction by then: 2 top jobs left, 40 s
    assert snapshots[first_top]["truth"] == 2 * COSTS[2]
    assert snapshots[first_top]["eta"] == Eta(2 * COSTS[2])
    for s in snapshots[first_top:]:
        assert s["eta"].seconds == pytest.approx(s["truth"])


def test_the_rate_over_finished_items_reads_far_too_low_where_the_ladders_does_not():
    """The issue's bar: when the cheap stage ends, tqdm's rule says seconds are left while
    minutes are; the ladder's estimate is unmarked only when it is the expected work."""
    snapshots = simulate(items=10, workers=1)
    end_of_first = max(k for k, s in enumerate(snapshots) if s["stage"] == 0)
    s = snapshots[end_of_first]
    assert s["truth"] == 5 * COSTS[1] + 3 * COSTS[2]  # 85 s
    assert s["rate"].seconds < s["truth"] / 5 and not s["rate"].at_least  # 5 of 10 in 10 s
    assert s["eta"].at_least  # no stage above has reported: a bound, said as one


def settled(snapshots: list[dict]) -> list[dict]:
    """The snapshots after the last of the results that came at the same time."""
    return [
        s
        for s, after in zip(snapshots, [*snapshots[1:], {"now": None}], strict=True)
        if after["now"] != s["now"]
    ]


def test_workers_in_parallel_spend_the_work_left_at_the_rate_measured():
    """Two workers: the worker-seconds left over worker-seconds done per second of clock."""
    one = simulate(items=16, workers=1)
    two = simulate(items=16, workers=2)
    assert two[-1]["now"] < one[-1]["now"]  # the pool did run in parallel
    points = settled(two)
    first_top = next(k for k, s in enumerate(points) if s["stage"] == len(COSTS) - 1)
    for s in points[:first_top]:
        assert s["eta"].at_least and s["eta"].seconds <= s["truth"]
    for s in points[first_top:]:
        assert not s["eta"].at_least and s["eta"].seconds == pytest.approx(s["truth"])


def test_nothing_is_estimated_before_a_cost_is_measured():
    eta = LadderEta(3, [0, 1, 2])  # a resumed sweep: designs waiting at different rungs
    assert eta.eta(5.0) is None and eta.untimed() == [0, 1, 2]
    eta.result(0, 1.0, goes_on=True)
    assert eta.untimed() == [1, 2] and eta.eta(1.0) == Eta(3.0, at_least=True)  # 1 s each
    eta = LadderEta(3, [2])
    eta.result(2, None, goes_on=False)  # a job given up: no cost
    assert eta.eta(5.0) == Eta(0.0)  # nothing waits any more


def test_rate_rule_and_clock_text():
    assert rate_eta(10.0, 0, 5) is None
    assert rate_eta(10.0, 2, 3) == Eta(15.0)
    assert rate_eta(10.0, 2, 0) == Eta(0.0)
    assert clock_text(202) == "03:22" and clock_text(3723) == "1:02:03"
    assert Eta(5.4, at_least=True).text() == ">= 00:05"
