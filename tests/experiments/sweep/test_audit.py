"""The audit (issue 21): designs that reach the verdict whatever the rungs below it say, and
climb no further unless they work. It measures what a rung that stops designs before the
verdict on a test (the screen) threw away, in every run, at the cost of verdicts only (the
holdout climbs the planning rungs too)."""

from __future__ import annotations

from pathlib import Path

import pytest
from sweep_fixtures import TINY
from test_sound_pruning import _holdout_of, _store

from experiments.sweep.config import ConfigError, config_from_dict
from experiments.sweep.ladder import audited, goes_on, pending_jobs, run_sweep
from experiments.sweep.summary import summarise, summary_table

GEOMETRIC = TINY["ladder"][0]
AUDITED = {
    **TINY,
    "designs": {"count": 8, "seed": 1},
    "ladder": [{"level": "screen"}, {"level": "passive"}, GEOMETRIC],
    "holdout": {"fraction": 0.25, "seed": 7},
    "audit": {"fraction": 0.5, "seed": 11},
}


def test_the_audit_is_read_and_a_config_without_one_keeps_its_results_key():
    config = config_from_dict(AUDITED)
    assert (config.audit_fraction, config.audit_seed) == (0.5, 11)
    assert len(audited(config)) == 4
    plain = {k: v for k, v in AUDITED.items() if k != "audit"}
    assert "audit" not in config_from_dict(plain).to_dict()
    assert config_from_dict(plain).results_key() != config.results_key()
    with pytest.raises(ConfigError, match=r"audit\.fraction"):
        config_from_dict({**AUDITED, "audit": {"fraction": 2}})


def test_an_audited_design_reaches_the_verdict_and_no_further_unless_it_works():
    config = config_from_dict(AUDITED)
    audit = audited(config)
    inside = min(audit - _holdout_of(config))
    outside = min(set(range(8)) - audit - _holdout_of(config))
    assert goes_on(config, 0, "infeasible", inside, set(), audit)  # screen failed: verdict
    assert not goes_on(config, 1, "infeasible", inside, set(), audit)  # fails: stops
    assert goes_on(config, 1, "feasible", inside, set(), audit)  # works: climbs on
    assert not goes_on(config, 0, "infeasible", outside, set(), audit)
    done = {(inside, "screen"): "infeasible", (outside, "screen"): "infeasible"}
    values = {inside: [0.0] * 12, outside: [0.0] * 12}
    jobs = pending_jobs(config, values, set(), done, audit)
    assert [(j["design_id"], j["level"]) for j in jobs] == [(inside, "passive")]


def test_the_screens_recall_and_what_it_threw_away_rest_on_the_audit(tmp_path: Path):
    """Every audited design has its verdict: one design the screen failed works, so the
    screen's recall is 1 of 2 on the audit (holdout included), the pipeline's cost is
    replayed on every audited design, and the estimate of what the ladder threw away comes
    from the audit."""
    config = config_from_dict(AUDITED)
    holdout, audit = _holdout_of(config), audited(config)
    sample = sorted(holdout | audit)
    plan: dict[int, dict[str, str]] = {}
    for d in range(8):
        if d not in sample:
            plan[d] = {"screen": "infeasible"}
    lost, kept = sample[0], sample[1]
    for d in sample:
        plan[d] = {"screen": "infeasible", "passive": "infeasible"}
        if d in holdout:
            plan[d]["geometric"] = "unknown"
    plan[lost] = {**plan[lost], "passive": "feasible", "geometric": "feasible"}
    plan[kept] = {
        **plan[kept],
        "screen": "feasible",
        "passive": "feasible",
        "geometric": "feasible",
    }
    summary = summarise(_store(tmp_path / "results.sqlite", config, plan, holdout))
    screen = next(p for p in summary["pruning"] if p["level"] == "screen")
    assert (screen["recall_basis"], screen["recall_n"], screen["thrown_away"]) == (
        "the audit",
        2,
        [lost],
    )
    pipe = next(p for p in summary["pipelines"] if p["rungs"] == ["screen", "passive"])
    assert (pipe["n"], pipe["basis"]) == (len(sample), "the audit")
    # planning rungs' costs of failing designs are known only on the holdout
    geometric_pipe = next(p for p in summary["pipelines"] if p["rungs"] == ["geometric", "passive"])
    assert (geometric_pipe["n"], geometric_pipe["basis"]) == (len(holdout), "the holdout")
    assert summary["thrown_away"]["holdout_pruned"] == len(sample) - 1
    assert "(audit n=" in summary_table(summary)


def test_a_run_with_a_full_audit_gives_every_design_its_verdict(tmp_path: Path):
    config = config_from_dict(
        {**AUDITED, "ladder": [{"level": "screen"}, {"level": "passive"}], "audit": {"fraction": 1}}
    )
    summary = summarise(run_sweep(config, tmp_path))
    passive = next(lv for lv in summary["levels"] if lv["level"] == "passive")
    screen = next(lv for lv in summary["levels"] if lv["level"] == "screen")
    assert passive["evaluated"] == screen["evaluated"] - screen["degenerate"]
    row = next(p for p in summary["pruning"] if p["level"] == "screen")
    assert row["recall_basis"] in ("the audit", "every design")
