"""The robust objective (issue 34): design centering maximises the smallest normalised
margin (experiments.margins.robustness) subject to the verdict's target. Read as
specifications, on a synthetic margins function whose acceptable region is a box (a known
centre), with budgets in margins evaluations."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from experiments.margins.robustness import robustness
from experiments.optimize import store
from experiments.optimize.centering import CenteringSettings, design_centering
from experiments.optimize.config import (
    ROBUSTNESS,
    OptimizeConfigError,
    config_from_dict,
    load_config,
)
from experiments.optimize.report import summary_text, write_report
from experiments.optimize.run import DATABASE, optimise, robust_measure
from feeders.design import DESIGN_SPACE, PARAMETER_NAMES, preset

LOW, HIGH = DESIGN_SPACE.low, DESIGN_SPACE.high
WIDTH = HIGH - LOW
RESOLUTION = 1 / 128


class Region:
    """A synthetic margins function: the design works when every parameter lies in
    [a, b] (a box inside Table 2's: a known centre) and ``fails(values)`` is false; each
    axis's interval is [a, b] (its side at the box's edge when a or b is); mu's is fixed."""

    def __init__(self, a, b, fails=None) -> None:
        self.a, self.b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        self.fails = fails or (lambda values: False)
        self.calls: list[list[float]] = []

    @property
    def centre(self) -> np.ndarray:
        return 0.5 * (self.a + self.b)

    def __call__(self, values) -> dict[str, Any]:
        x = np.asarray(values, dtype=float)
        self.calls.append(x.tolist())
        works = bool(np.all(x >= self.a) and np.all(x <= self.b)) and not self.fails(x)
        rows = []
        for i, name in enumerate(PARAMETER_NAMES):
            rows.append(row(name, "design", x[i], self.a[i], self.b[i], LOW[i], HIGH[i]))
        rows.append(row("mu", "friction", 0.05, 0.0, 0.25, 0.0, 0.3))
        verdict = {"orientations": {"heavy leading": {"mean_exit_time_s": 2.0}}}
        return {
            "design": "synthetic",
            "target": 0.9,
            "drops_per_value": 20,
            "seed": 0,
            "works": works,
            "verdict": verdict,
            "margins": rows if works else [],
            "cost": {"trials": 1, "drops": 2, "wall_time_s": 0.0, "workers": 1},
        }


def side(limit: float, edge: float, step: float) -> dict[str, Any]:
    at_edge = limit == edge
    outside = None if at_edge else {"value": limit + step}
    return {"limit": limit, "at_box_edge": at_edge, "first_outside": outside}


def row(name, kind, nominal, a, b, low, high) -> dict[str, Any]:
    res = RESOLUTION * (high - low)
    return {
        "parameter": name,
        "kind": kind,
        "unit": "-",
        "meaning": name,
        "box_source": "Table 2",
        "nominal": float(nominal),
        "box": [float(low), float(high)],
        "interval": [float(a), float(b)],
        "low": side(float(a), float(low), -res),
        "high": side(float(b), float(high), res),
    }


def inner_region(fraction_low=0.2, fraction_high=0.6) -> Region:
    return Region(LOW + fraction_low * WIDTH, LOW + fraction_high * WIDTH)


def start_in(region: Region) -> list[float]:
    """A start inside the region, off its centre by a different amount per parameter."""
    offsets = np.linspace(0.05, 0.9, len(PARAMETER_NAMES))
    return (region.a + offsets * (region.b - region.a)).tolist()


def centre(region: Region, step: float, budget: int, **kwargs) -> Any:
    settings = CenteringSettings(budget=budget, step=step, **kwargs)
    return design_centering(start_in(region), PARAMETER_NAMES, LOW, HIGH, region, settings)


def test_a_full_step_moves_the_nominal_to_the_centre_of_a_box_region_and_stops_there():
    region = inner_region()
    chain = centre(region, step=1.0, budget=10)
    assert np.allclose(chain.best, region.centre, rtol=0, atol=1e-12)
    assert len(region.calls) == 2  # the start, the move to the centre; no move is left
    assert chain.stopped == "at the centre: no move left"
    assert robustness(chain.best_margins).value == pytest.approx(0.2)


def test_damped_steps_converge_to_the_centre_within_the_budget_of_evaluations():
    region = inner_region()
    chain = centre(region, step=0.5, budget=12)
    assert len(region.calls) == 12  # the budget is a count of margins evaluations
    assert chain.stopped == "budget spent"
    assert all(s.accepted for s in chain.steps)  # each damped step is more robust
    assert np.max(np.abs(np.asarray(chain.best) - region.centre) / WIDTH) < 0.4 * 0.5**11


def test_a_side_at_the_box_edge_counts_as_ending_there_and_moves_only_away_from_the_limit():
    a = LOW + 0.2 * WIDTH
    a[0] = a[1] = LOW[0]  # two parameters' regions reach the box's low edge
    a[1] = LOW[1]
    region = Region(a, LOW + 0.6 * WIDTH)
    start = np.asarray(start_in(region))
    start[0] = LOW[0] + 0.5 * WIDTH[0]  # above its interval's centre (0.3): moves down
    start[1] = LOW[1] + 0.1 * WIDTH[1]  # below it: its limited (high) room is the larger
    settings = CenteringSettings(budget=4, step=1.0)
    chain = design_centering(start.tolist(), PARAMETER_NAMES, LOW, HIGH, region, settings)
    assert chain.best[0] == pytest.approx(LOW[0] + 0.3 * WIDTH[0])
    assert chain.best[1] == start[1]  # moving up would shrink the room that counts


def test_focus_moves_the_bottlenecks_first_and_still_reaches_the_centre():
    region = inner_region()
    chain = centre(region, step=1.0, budget=30, focus=2.0)
    first_move = np.asarray(chain.steps[1].values)
    start = np.asarray(start_in(region))
    moved = ~np.isclose(first_move, start)
    assert moved.any() and not moved.all()  # the tightest parameters only
    assert np.allclose(chain.best, region.centre, rtol=0, atol=1e-9)


def test_a_design_that_does_not_work_is_never_accepted():
    region = inner_region()
    # the verdict fails past a quarter of the way to the centre on the first parameter,
    # though the margins' interval (one axis at a time) reaches further: the centring move
    # there is rejected and the step halved
    start = start_in(region)
    limit = start[0] + 0.25 * (region.centre[0] - start[0])
    region.fails = lambda x: x[0] > limit
    chain = centre(region, step=1.0, budget=12, min_step=0.01)
    rejected = [s for s in chain.steps if not s.works]
    assert rejected and not any(s.accepted for s in rejected)
    assert all(s.works for s in chain.steps if s.accepted)
    assert chain.best[0] <= limit
    assert region(chain.best)["works"]
    assert robustness(chain.best_margins).value > robustness(region(start)).value


def test_a_start_that_does_not_work_is_not_moved():
    region = inner_region()
    settings = CenteringSettings(budget=5)
    outside = (LOW + 0.9 * WIDTH).tolist()
    chain = design_centering(outside, PARAMETER_NAMES, LOW, HIGH, region, settings)
    assert chain.best is None and len(chain.steps) == 1
    assert chain.stopped == "the start does not work"


class Report:
    def __init__(self, data: dict[str, Any]) -> None:
        self.data = data

    def to_dict(self) -> dict[str, Any]:
        return self.data


class SubjectMeasure:
    """The margins' measurement as the optimiser calls it (subject, settings, workers,
    on_axis), answered by a synthetic region; counts its calls."""

    def __init__(self, region: Region) -> None:
        self.region = region
        self.calls = 0

    def __call__(self, subject, settings, workers, on_axis=None):
        self.calls += 1
        values = [subject.values[n] for n in PARAMETER_NAMES]
        return Report(self.region(values))


ROBUST = {
    "name": "tiny-robust",
    "feeder": {"friction": 0.05, "restitution": 0.3},
    "objective": {"trials": 2, "seed": 0},
    "goal": "robustness",
    "centering": {"budget": 6, "step": 0.5},
    "start": {"presets": ["table3"]},
    "final": {"trials": 2, "seed": 1000, "target": 0.3, "candidates": 2},
    "workers": 1,
}


class Db:
    def __init__(self, db) -> None:
        self.db = db


def test_a_stopped_centring_resumes_from_the_store_without_measuring_again(tmp_path: Path):
    config = config_from_dict(ROBUST)
    region = inner_region()
    space_names = PARAMETER_NAMES
    from experiments.optimize.run import designed

    space = designed(config)
    settings = config.centering
    db = store.connect(tmp_path / DATABASE)
    try:
        measure = SubjectMeasure(region)
        of = robust_measure(Db(db), config, space, measure=measure)  # type: ignore[arg-type]
        stopped = design_centering(start_in(region), space_names, LOW, HIGH, of, settings, budget=3)
        assert measure.calls == 3
        whole = design_centering(start_in(region), space_names, LOW, HIGH, of, settings)
        assert measure.calls == 6  # the 3 stored replayed, 3 new
        assert [s.values for s in whole.steps[:3]] == [s.values for s in stopped.steps]
        again = design_centering(start_in(region), space_names, LOW, HIGH, of, settings)
        assert measure.calls == 6  # everything stored
        assert again.to_dict() == whole.to_dict()
    finally:
        db.close()


@pytest.mark.slow  # ~10 s
def test_the_robust_goal_runs_end_to_end_and_a_run_again_measures_nothing(tmp_path: Path):
    table3 = preset("table3").to_vector()
    # table3 0.01 of each box below its upper limit and 0.03 above its lower one where the
    # box allows (elsewhere the whole box): centring moves it down, a little (the optimum's
    # real verdict on the fresh trials must still work)
    a, b = table3 - 0.03 * WIDTH, table3 + 0.01 * WIDTH
    inside = (a >= LOW) & (b <= HIGH)
    region = Region(np.where(inside, a, LOW), np.where(inside, b, HIGH))
    config = config_from_dict(ROBUST)
    measure = SubjectMeasure(region)
    out = optimise(config, tmp_path, measure=measure)
    robust = out["robust"]
    # the chain's evaluations (at most its budget); table3, the baseline, was its start
    assert measure.calls == robust["evaluations"] <= 6
    assert robust["evaluations"] >= 2
    assert robust["optimum"]["value"] > robust["baseline"]["value"]
    assert out["margins"]["design"] == "optimum"
    assert out["baseline_margins"]["design"] == "table3"
    optimum = [out["optimum"]["values"][n] for n in PARAMETER_NAMES]
    best = robust["chains"][0]["best"]
    assert optimum == best
    calls = measure.calls
    again = optimise(config, tmp_path, measure=measure)
    assert measure.calls == calls  # every evaluation came back from the store
    assert again["robust"] == robust
    page = write_report(tmp_path, config, again).read_text()
    assert "How it was found: the robust objective" in page
    assert "What it maximised" in page
    assert "robust objective: the robustness" in summary_text(again)


def test_the_shipped_robust_config_loads():
    config = load_config("robust")
    assert config.goal == ROBUSTNESS
    assert config.centering.budget >= 1
    assert config.final_trials == 150
    assert config.presets == ("table3",)


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"goal": "fastest"}, "goal"),
        ({"goal": "eq10", "methods": [{"method": "powell", "budget": 3}]}, "centering"),
        ({"centering": {"budget": 0}}, "centering.budget"),
        ({"centering": {"step": 2.0}}, "centering.step"),
        ({"centering": {"stride": 1}}, "stride"),
    ],
)
def test_bad_robust_fields_are_refused_naming_the_field(change, field):
    with pytest.raises(OptimizeConfigError, match=field):
        config_from_dict({**ROBUST, **change})


def test_an_eq10_config_is_unchanged_by_the_robust_goal():
    config = load_config("optimize")
    assert "goal" not in config.to_dict() and "centering" not in config.to_dict()
    with pytest.raises(OptimizeConfigError, match="methods"):
        config_from_dict({k: v for k, v in ROBUST.items() if k not in ("goal", "centering")})


def test_equal_robustness_up_to_rounding_is_a_tie_broken_by_the_exit_time():
    from experiments.optimize.centering import better

    region = inner_region()
    old = region(region.centre.tolist())
    new = region((region.centre + 1e-15).tolist())  # the same robustness, but for rounding
    slower = {**new, "verdict": {"orientations": {"x": {"mean_exit_time_s": 2.5}}}}
    faster = {**new, "verdict": {"orientations": {"x": {"mean_exit_time_s": 1.5}}}}
    assert not better(slower, old)
    assert better(faster, old)
    assert not better({**faster, "works": False}, old)


def test_random_moves_after_a_rejected_centring_move_are_seeded_and_counted():
    region = inner_region()
    start = start_in(region)
    limit = start[0] + 1e-3 * WIDTH[0]  # every centring move of the first parameter fails
    region.fails = lambda x: x[0] > limit

    def run() -> Any:
        settings = CenteringSettings(budget=9, step=1.0, explore=2, spread=0.05, seed=3)
        return design_centering(start, PARAMETER_NAMES, LOW, HIGH, region, settings)

    first, second = run(), run()
    kinds = [s.kind for s in first.steps]
    assert kinds[:4] == ["start", "centre", "random", "random"]
    assert len(first.steps) <= 9
    assert first.to_dict() == second.to_dict()  # the same seed, the same moves
    assert all(s.works for s in first.steps if s.accepted)
