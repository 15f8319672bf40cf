"""The sweep's progress bar tells the truth (issue 25: its bars always read 100%, their total
growing as jobs finished, with no time estimate): one bar over the designs, whose total is
fixed when it starts and is reached exactly when the sweep ends, fresh or resumed.

The evaluations are hand-made (no planning): what is specified is the counting, not OMPL."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import pytest
from sweep_fixtures import fake_result, tiny_config

from experiments.cli.run_sweep import SweepProgress
from experiments.sweep.ladder import run_sweep

LEVELS = ("geometric", "kinematic", "dynamic")


def climb_some(job: dict) -> dict:
    """Feasible unless (design + rung) is a multiple of 3: designs stop at every rung."""
    status = "infeasible" if (job["design_id"] + job["rung"]) % 3 == 0 else "feasible"
    return fake_result(job["design_id"], job["level"], status, 0.01)


class Recorder(SweepProgress):
    """The bar as drawn into a string, with its total when it started and its count at the
    end; and every event."""

    def __init__(self) -> None:
        super().__init__(quiet=False, stream=io.StringIO())
        self.events: list[tuple[str, dict[str, Any]]] = []
        self.started_total: int | None = None
        self.ended: tuple[int, int] | None = None

    def __call__(self, event: str, info: dict[str, Any]) -> None:
        self.events.append((event, info))
        super().__call__(event, info)
        if event == "start":
            self.started_total = self.bar.total

    def close(self) -> None:
        if self.bar is not None:
            self.ended = (self.bar.n, self.bar.total)
        super().close()


def _sweep(out: Path) -> Recorder:
    bars = Recorder()
    try:
        run_sweep(tiny_config(), out, progress=bars, evaluate=climb_some)
    finally:
        bars.close()
    return bars


def test_the_bars_total_is_the_designs_from_the_start_and_is_reached_at_the_end(tmp_path):
    bars = _sweep(tmp_path)
    designs = tiny_config().count
    assert bars.started_total == designs
    assert bars.ended == (designs, designs)
    evaluations = [info for event, info in bars.events if event == "result"]
    assert len(evaluations) > designs  # some designs climbed: more evaluations than designs
    assert sum(info["finished"] for info in evaluations) == designs
    drawn = bars.stream.getvalue()
    assert f"{designs}/{designs}" in drawn and "100%" in drawn
    for level in LEVELS:
        assert level in drawn  # each level's feasible / evaluated counts beside the bar


@pytest.mark.slow  # ~10 s
def test_a_finished_sweep_started_again_starts_complete_and_runs_nothing(tmp_path):
    _sweep(tmp_path)
    again = _sweep(tmp_path)
    designs = tiny_config().count
    assert [event for event, _ in again.events] == ["start"]
    assert again.events[0][1]["finished"] == designs
    assert again.ended == (designs, designs)


@pytest.mark.slow  # ~6 s
def test_quiet_draws_nothing(tmp_path):
    stream = io.StringIO()
    bars = SweepProgress(quiet=True, stream=stream)
    run_sweep(tiny_config(), tmp_path, progress=bars, evaluate=climb_some)
    bars.close()
    assert stream.getvalue() == ""


class StepClock:
    """A clock (s) the test moves."""

    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_the_time_left_counts_each_levels_cost_not_the_designs_finished_first():
    """Issue 39: 10 designs, 1 s each at the first level, 5 of them stopped there; a rate over
    designs finished says 10 s are left when the 5 others' next levels are still to come.
    The line says it is a lower bound ('>=') until the level above has reported, then the
    expected work: 4 designs left at 5 s each (the worker times of the events)."""
    stream, clock = io.StringIO(), StepClock()
    bars = SweepProgress(quiet=False, stream=stream, clock=clock)
    bars("start", {"levels": list(LEVELS[:2]), "done": {}, "designs": 10, "finished": 0,
                   "waiting": [0] * 10})  # fmt: skip
    for design in range(10):
        clock.now += 1.0
        result = {"rung": 0, "level": "geometric", "status": "feasible", "wall_time_s": 1.0}
        bars("result", {**result, "finished": design % 2 == 1})
    clock.now += 5.0
    bars("result", {"rung": 1, "level": "kinematic", "status": "feasible",
                    "wall_time_s": 5.0, "finished": True})  # fmt: skip
    bars.close()
    lines = stream.getvalue().splitlines()
    at_five = next(line for line in lines if " 5/10 " in line)
    assert "ETA >= 00:05" in at_five  # 5 waiting at kinematic, taken at geometric's 1 s
    assert at_five.endswith("; not yet timed: kinematic")
    at_six = next(line for line in lines if " 6/10 " in line)
    assert "elapsed 00:15, ETA 00:20" in at_six  # 4 x 5 s at 15 s of work in 15 s
    assert "not yet timed" not in at_six
