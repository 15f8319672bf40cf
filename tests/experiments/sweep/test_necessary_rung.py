"""The necessary-conditions rung (issue 21): a cheap rung before the verdict whose
"infeasible" is a proof (docs/necessary.md), so the sweep prunes on it without losing a
design that works, and the summary counts its stops as failing designs, not lost ones."""

from __future__ import annotations

from pathlib import Path

import pytest
from sweep_fixtures import TINY
from test_sound_pruning import _holdout_of, _store

from experiments.sweep.config import ConfigError, config_from_dict
from experiments.sweep.job import evaluate_design, sweep_job
from experiments.sweep.summary import summarise, summary_table
from feeders.design import preset

GEOMETRIC = TINY["ladder"][0]
NECESSARY_FIRST = {
    **TINY,
    "designs": {"count": 8, "seed": 1},
    "ladder": [{"level": "necessary"}, {"level": "passive"}, GEOMETRIC],
    "holdout": {"fraction": 0.25, "seed": 7},
}


def test_the_rung_reads_its_tolerance_and_entry_noise_and_prunes():
    config = config_from_dict(NECESSARY_FIRST)
    rung = config.ladder[0]
    assert rung.prunes and rung.perturbations == {"tolerance": 0.01, "position": 0.05, "yaw": 0.05}
    with pytest.raises(ConfigError, match=r"ladder\[0\]\.perturbations"):
        config_from_dict(
            {**NECESSARY_FIRST, "ladder": [{"level": "necessary", "perturbations": {"speed": 1}}]}
        )


@pytest.mark.parametrize(("name", "status"), [("table3", "feasible"), ("fig7a", "infeasible")])
def test_a_design_is_infeasible_only_when_a_necessary_test_fails(name, status):
    """table3 works; fig7a, which the paper finds infeasible, fails the sliced test."""
    config = config_from_dict(NECESSARY_FIRST)
    job = sweep_job(config, 0, [float(v) for v in preset(name).to_vector()], 0)
    result = evaluate_design(job)
    assert result["status"] == status
    if status == "infeasible":
        assert result["reason"] == "fails the necessary sliced test"


def test_its_stops_are_failing_designs_not_lost_ones(tmp_path: Path):
    """Designs 0-1 (outside the holdout) fail the necessary tests: no verdict, yet the
    fraction that works is over every design, recall rests on every design that works, and
    nothing is reported thrown away (a proof throws away no design that works)."""
    config = config_from_dict(NECESSARY_FIRST)
    holdout = _holdout_of(config)
    outside = [d for d in range(8) if d not in holdout]
    plan: dict[int, dict[str, str]] = {}
    for d in outside[:2]:
        plan[d] = {"necessary": "infeasible"}
    for d in outside[2:4]:
        plan[d] = {"necessary": "feasible", "passive": "feasible", "geometric": "feasible"}
    for d in outside[4:]:
        plan[d] = {"necessary": "feasible", "passive": "infeasible"}
    for d in holdout:
        plan[d] = {"necessary": "feasible", "passive": "infeasible", "geometric": "unknown"}
    summary = summarise(_store(tmp_path / "results.sqlite", config, plan, holdout))
    passive = summary["passive"]
    assert (passive["works_basis"], passive["works_n"]) == ("every design", 8)
    # 6 judged, 2 proven to fail: the fraction is over all 8
    assert (
        "2 of 6 designs judged work, 0 undecided; 2 of 8 in every design (6 judged, 2 proven to "
        "fail below) work: 25% [7%, 59%]" in summary_table(summary)
    )
    geometric = next(p for p in summary["pruning"] if p["level"] == "geometric")
    assert (geometric["recall_basis"], geometric["recall_n"]) == ("every design", 2)
    assert summary["thrown_away"] is None


def test_each_pipelines_speed_up_has_a_paired_interval(tmp_path: Path):
    """The holdout's designs cost alike (necessary 1 s, passive 0.2 s, geometric 1 s in the
    fixture), so every resample gives the same ratio: the interval is the point; passive
    alone is 1 exactly."""
    config = config_from_dict(NECESSARY_FIRST)
    holdout = _holdout_of(config)
    plan = {
        d: {"necessary": "feasible", "passive": "infeasible", "geometric": "feasible"}
        for d in range(8)
    }
    summary = summarise(_store(tmp_path / "results.sqlite", config, plan, holdout))
    by_rungs = {tuple(p["rungs"]): p for p in summary["pipelines"]}
    assert by_rungs[("passive",)]["speedup_ci"] == [1.0, 1.0]
    for pipe in summary["pipelines"]:
        low, high = pipe["speedup_ci"]
        assert low == pytest.approx(pipe["speedup"]) and high == pytest.approx(pipe["speedup"])
    assert by_rungs[("necessary", "passive")]["speedup"] == pytest.approx(0.2 / 1.2)
