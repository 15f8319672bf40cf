"""The optimiser's progress bars have totals fixed when they start, and reach them (issue 25):
the evaluations (starts, every run's budget, table3's), then the verdicts on fresh draws."""

from __future__ import annotations

import io
from typing import Any

from experiments.cli.optimize import OptimizeProgress
from experiments.optimize.config import config_from_dict
from experiments.optimize.run import evaluations_total, optimise

TINY = {
    "name": "tiny",
    "feeder": {"friction": 0.05, "restitution": 0.3},
    "objective": {"trials": 2, "seed": 0},
    "start": {"presets": ["table3", "fig7a"]},
    "methods": [
        {"method": "powell", "budget": 3, "seeds": [0]},
        {"method": "nelder-mead", "budget": 2, "seeds": [0], "start": "best"},
    ],
    "final": {"trials": 2, "seed": 1000, "candidates": 2},
    "workers": 2,
}


class Recorder(OptimizeProgress):
    """Each bar's total when it started and (count, total) when it ended."""

    def __init__(self) -> None:
        super().__init__(quiet=False, stream=io.StringIO())
        self.started: list[int] = []
        self.ended: list[tuple[int, int]] = []

    def __call__(self, event: str, info: dict[str, Any]) -> None:
        super().__call__(event, info)
        if event in ("start", "verdicts"):
            self.started.append(self.bar.total)

    def close(self) -> None:
        if self.bar is not None:
            self.ended.append((self.bar.n, self.bar.total))
        super().close()


def test_the_evaluations_total_counts_starts_budgets_and_table3():
    assert evaluations_total(config_from_dict(TINY), starts=2) == 2 + 3 + 2 + 1


def test_each_bar_ends_at_the_total_it_started_with(tmp_path):
    bars = Recorder()
    try:
        optimise(config_from_dict(TINY), tmp_path, progress=bars)
    finally:
        bars.close()
    assert bars.started == [8, 2 + 2]  # evaluations; the candidates', optimum's, table3's
    assert bars.ended == [(8, 8), (4, 4)]
    assert "100%" in bars.stream.getvalue()


def test_a_run_that_stops_before_its_budget_moves_the_bar_to_it():
    bars = OptimizeProgress(quiet=False, stream=io.StringIO())
    bars("start", {"evaluations": 5})
    best = {"value": 1.5, "both": 0}
    for n in range(2):
        bars("evaluation", {"run": "nelder-mead/seed0", "n": n, "budget": 5, "best": best})
    bars("run end", {"run": "nelder-mead/seed0", "unspent": 3})
    assert (bars.bar.n, bars.bar.total) == (5, 5)
    bars.close()


def test_the_margins_bar_counts_the_sixteen_axes():
    bars = OptimizeProgress(quiet=False, stream=io.StringIO())
    bars("verdicts", {"verdicts": 6, "trials": 150})
    bars("margins", {"axes": 16})
    assert (bars.bar.n, bars.bar.total) == (0, 16)
    for name in ["a", "b", "c", "d", "e", "fx", "fy", "gx", "gy", "r", "theta", "alpha"]:
        bars("axis", {"axis": name})
    for name in ["mu", "length", "width", "heavy_fraction"]:
        bars("axis", {"axis": name})
    assert (bars.bar.n, bars.bar.total) == (16, 16)
    assert "margins of the optimum" in bars.stream.getvalue()
    bars.close()
