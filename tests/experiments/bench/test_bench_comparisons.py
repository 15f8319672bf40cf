"""The arithmetic of the comparisons and of the interleaved timing, on made-up data."""

from __future__ import annotations

import math

import pytest

from experiments.bench.comparisons import cost_at_error
from experiments.bench.timing import interleaved_seconds
from experiments.cli.bench import SECTIONS as CLI_SECTIONS


def _pt(wall: float, error: float) -> dict:
    return {"wall_per_sim_s": wall, "errors": {"error": error}}


def test_cost_at_error_interpolates_log_log():
    curve = [_pt(1e-3, 1e-2), _pt(1e-2, 1e-3), _pt(1e-1, 1e-4)]
    # on a line of slope -1 in log-log, error 3.16e-3 is at wall 3.16e-3
    assert cost_at_error(curve, 10**-2.5) == pytest.approx(10**-2.5, rel=1e-12)
    assert cost_at_error(curve, 1.0) == 1e-3  # even the cheapest point is accurate enough
    assert cost_at_error(curve, 1e-5) is None  # no measured point reaches it
    assert cost_at_error([_pt(1e-3, 1e-2), _pt(1e-2, 0.0)], 1e-4) == 1e-2


def test_interleaved_seconds_times_every_run_each_round():
    order = []
    runs = {k: (lambda: None, lambda k=k: order.append(k)) for k in "abc"}
    out = interleaved_seconds(runs, repeats=3)
    assert {k: len(v) for k, v in out.items()} == {"a": 3, "b": 3, "c": 3}
    assert all(t >= 0.0 and math.isfinite(t) for v in out.values() for t in v)
    assert order[3:6] == ["b", "c", "a"]  # round 1 starts one further along
    with pytest.raises(ValueError, match="repeats"):
        interleaved_seconds(runs, 0)


def test_cli_sections_are_the_suites():
    from experiments.bench.suite import SECTIONS

    assert CLI_SECTIONS == SECTIONS
