"""The screen rung (issue 21): coarse-step drops before the verdict that fail a design only
by a sequential test with a stated error (docs/verdict.md). The sweep stops what it fails,
sends on what it passes or leaves undecided, counts its stops as failing designs in the
passive fraction, and measures what it threw away on the holdout only (its stops have no
verdict)."""

from __future__ import annotations

from pathlib import Path

import pytest
from sweep_fixtures import TINY
from test_sound_pruning import _holdout_of, _store

from experiments.sweep.config import ConfigError, config_from_dict
from experiments.sweep.job import evaluate_design, screen_seed, sweep_job, verdict_seed
from experiments.sweep.ladder import climbs
from experiments.sweep.summary import summarise, summary_table
from feeders.design import preset

GEOMETRIC = TINY["ladder"][0]
SCREEN_FIRST = {
    **TINY,
    "designs": {"count": 8, "seed": 1},
    "ladder": [{"level": "screen"}, {"level": "passive"}, GEOMETRIC],
    "holdout": {"fraction": 0.25, "seed": 7},
}


def test_the_rung_reads_its_settings_and_names_a_bad_one():
    rung = config_from_dict(SCREEN_FIRST).ladder[0]
    assert rung.verdict["step"] == 0.004 and rung.verdict["false_fails"] == 0.001
    assert rung.to_dict()["screen"] == rung.verdict and not rung.prunes
    with pytest.raises(ConfigError, match=r"ladder\[0\]\.screen\.false_fails"):
        config_from_dict(
            {**SCREEN_FIRST, "ladder": [{"level": "screen", "screen": {"false_fails": 2}}]}
        )
    with pytest.raises(ConfigError, match=r"ladder\[0\]\.screen"):
        config_from_dict({**SCREEN_FIRST, "ladder": [{"level": "screen", "screen": {"alpha": 1}}]})


def test_a_failed_screen_stops_a_design_and_an_undecided_one_does_not():
    rung = config_from_dict(SCREEN_FIRST).ladder[0]
    assert not climbs(rung, "infeasible")
    assert climbs(rung, "unknown") and climbs(rung, "feasible")


def test_its_drops_are_drawn_apart_from_the_verdicts():
    assert {screen_seed(0, d) for d in range(50)}.isdisjoint(
        {verdict_seed(0, d) for d in range(50)}
    )


@pytest.mark.parametrize(("name", "status"), [("table3", "feasible"), ("fig5b", "infeasible")])
def test_a_design_that_works_passes_and_a_failing_one_is_failed(name, status):
    config = config_from_dict(SCREEN_FIRST)
    result = evaluate_design(sweep_job(config, 0, [float(v) for v in preset(name).to_vector()], 0))
    assert result["status"] == status
    if status == "infeasible":
        assert result["reason"].startswith("fails the screen from ")
        assert result["screen"]["decision"] == "fails"


def test_its_stops_count_as_failures_but_what_it_lost_is_measured_on_the_holdout(tmp_path: Path):
    """Two designs outside the holdout fail the screen: no verdict, yet the passive fraction
    is over every design (a failed test, as the verdict's own "fails"); the screen's recall
    and what the ladder threw away rest on the holdout, where one design the screen failed
    works; the geometric rung's recall is still a census of the designs that work."""
    config = config_from_dict(SCREEN_FIRST)
    holdout = sorted(_holdout_of(config))
    outside = [d for d in range(8) if d not in holdout]
    plan: dict[int, dict[str, str]] = {}
    for d in outside[:2]:
        plan[d] = {"screen": "infeasible"}
    for d in outside[2:4]:
        plan[d] = {"screen": "feasible", "passive": "feasible", "geometric": "feasible"}
    for d in outside[4:]:
        plan[d] = {"screen": "unknown", "passive": "infeasible"}
    plan[holdout[0]] = {"screen": "infeasible", "passive": "feasible", "geometric": "feasible"}
    plan[holdout[1]] = {"screen": "infeasible", "passive": "infeasible", "geometric": "unknown"}
    summary = summarise(_store(tmp_path / "results.sqlite", config, plan, set(holdout)))
    passive = summary["passive"]
    assert (passive["works_basis"], passive["works_n"]) == ("every design", 8)
    screen = next(p for p in summary["pruning"] if p["level"] == "screen")
    assert (screen["recall_basis"], screen["recall_n"], screen["thrown_away"]) == (
        "the holdout",
        1,
        [holdout[0]],
    )
    geometric = next(p for p in summary["pruning"] if p["level"] == "geometric")
    assert (geometric["recall_basis"], geometric["recall_n"]) == ("every design", 3)
    lost = summary["thrown_away"]
    assert lost["pruned"] == 2 and lost["holdout_pruned_working"] == [holdout[0]]
    assert "an estimated 1.0" in summary_table(summary)
