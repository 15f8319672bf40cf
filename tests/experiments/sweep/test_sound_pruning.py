"""Sound pruning only (issue 21): a planning rung whose planners find no path within their
budget has proved nothing (``unknown``), so by default the design climbs on; a rung prunes on
it only when its config says ``prunes: true`` (the paper's order, ``paper.yaml``). Recall is
measured on every design that works when the ladder lets them all climb, the designs that
work that a rung would throw away are named, and a ladder that prunes before the verdict
says how many working designs it threw away, as an estimate from the holdout."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pytest
from sweep_fixtures import TINY, fake_result, fake_verdict

from experiments.sweep import results_db
from experiments.sweep.config import ConfigError, config_from_dict, load_config
from experiments.sweep.ladder import climbs, pending_jobs
from experiments.sweep.report_html import thrown_away_parts
from experiments.sweep.summary import summarise, summary_table
from feeders.halton import halton_points

GEOMETRIC, KINEMATIC = TINY["ladder"][0], TINY["ladder"][1]
PASSIVE_FIRST = {
    **TINY,
    "designs": {"count": 8, "seed": 1},
    "ladder": [{"level": "passive"}, GEOMETRIC, KINEMATIC],
    "holdout": {"fraction": 0.25, "seed": 7},
}


def _config(ladder: list[dict], count: int = 8, fraction: float = 0.25):
    return config_from_dict(
        {**PASSIVE_FIRST, "designs": {"count": count, "seed": 1}, "ladder": ladder,
         "holdout": {"fraction": fraction, "seed": 7}}
    )  # fmt: skip


def test_a_planning_rung_does_not_prune_unknown_by_default_and_prunes_when_told() -> None:
    default = config_from_dict(PASSIVE_FIRST)
    told = _config([{"level": "passive"}, {**GEOMETRIC, "prunes": True}, KINEMATIC])
    assert not default.ladder[1].prunes and told.ladder[1].prunes
    assert climbs(default.ladder[1], "unknown") and not climbs(told.ladder[1], "unknown")
    for rung in (default.ladder[1], told.ladder[1]):
        assert climbs(rung, "feasible")
        assert not climbs(rung, "degenerate")
    # an older database's "infeasible" at a planning level meant not found within budget
    assert climbs(default.ladder[1], "infeasible") and not climbs(told.ladder[1], "infeasible")
    assert not climbs(default.ladder[0], "infeasible")  # the verdict says it fails


def test_resuming_sends_a_design_unknown_at_a_rung_that_does_not_prune_up_the_ladder() -> None:
    """Design 5 (not in the holdout) works and is unknown at geometric: its next job is
    kinematic by default, and none when geometric prunes."""
    default = config_from_dict(PASSIVE_FIRST)
    told = _config([{"level": "passive"}, {**GEOMETRIC, "prunes": True}, KINEMATIC])
    designs = {5: [0.0] * 12}
    done = {(5, "passive"): "feasible", (5, "geometric"): "unknown"}
    assert [j["level"] for j in pending_jobs(default, designs, set(), done)] == ["kinematic"]
    assert pending_jobs(told, designs, set(), done) == []
    assert [j["level"] for j in pending_jobs(told, designs, {5}, done)] == ["kinematic"]


def test_prunes_is_read_checked_and_only_a_non_default_value_changes_the_results_key() -> None:
    base = config_from_dict(PASSIVE_FIRST)
    assert base.to_dict()["ladder"][1]["prunes"] is False
    again = config_from_dict(base.to_dict())
    assert again == base and again.results_key() == base.results_key()
    told = _config([{"level": "passive"}, {**GEOMETRIC, "prunes": True}, KINEMATIC])
    assert told.results_key() != base.results_key()
    with pytest.raises(ConfigError, match=r"ladder\[1\]\.prunes = 'yes'; allowed: true, false"):
        _config([{"level": "passive"}, {**GEOMETRIC, "prunes": "yes"}, KINEMATIC])
    with pytest.raises(ConfigError, match=r"ladder\[0\]"):
        _config([{"level": "passive", "prunes": True}, GEOMETRIC])


def test_the_shipped_configs_prune_as_documented() -> None:
    """The default stops a design only on a test with a stated error: the screen, then the
    verdict; no planning rung prunes on a budget miss."""
    default = load_config("default").ladder
    assert [r.level for r in default if r.prunes] == []
    assert default[0].level == "screen" and default[1].level == "passive"
    paper = load_config("paper").ladder
    assert all(r.prunes for r in paper if r.level != "passive")


def _store(path: Path, config, plan: dict[int, dict[str, str]], holdout: set[int]) -> Path:
    """A results database of ``config`` holding ``plan``: design -> level -> status (1 s per
    planning evaluation; the passive rung 0.2 s, works or fails)."""
    db = results_db.connect(path)
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(config.count, config.seed)
        results_db.add_designs(
            db, ((i, i in holdout, list(points[i])) for i in range(config.count))
        )
        levels = [r.level for r in config.ladder]
        for d, statuses in plan.items():
            for level, status in statuses.items():
                if level == "passive":
                    works = status == "feasible"
                    verdict = fake_verdict(
                        "works" if works else "fails", 10 if works else 0, 10, 1.0
                    )
                    result = fake_result(d, level, status, 0.2, verdict)
                else:
                    result = fake_result(d, level, status, 1.0)
                results_db.record(db, result, levels.index(level), 1)
    finally:
        db.close()
    return path


def _holdout_of(config) -> set[int]:
    from experiments.sweep.ladder import holdout_ids

    return holdout_ids(config.count, config.holdout_fraction, config.holdout_seed)


def test_recall_rests_on_every_design_that_works_and_names_the_ones_a_rung_throws_away(
    tmp_path: Path,
) -> None:
    """Passive first, planning rungs that do not prune: the four designs that work (none in
    the holdout) climb every rung; geometric leaves design 3 unknown, kinematic designs 3
    and 4. The holdout's two designs fail. Recall: geometric 3 of 4, kinematic 2 of 4,
    geometric -> kinematic 2 of 4, on every design; precision on the holdout."""
    config = config_from_dict(PASSIVE_FIRST)
    holdout = _holdout_of(config)
    working = [d for d in range(8) if d not in holdout][:4]
    failing = [d for d in range(8) if d not in holdout][4:]
    plan: dict[int, dict[str, str]] = {}
    for d in working:
        plan[d] = {"passive": "feasible", "geometric": "feasible", "kinematic": "feasible"}
    plan[working[2]]["geometric"] = "unknown"
    plan[working[2]]["kinematic"] = "unknown"
    plan[working[3]]["kinematic"] = "unknown"
    for d in holdout:
        plan[d] = {"passive": "infeasible", "geometric": "feasible", "kinematic": "unknown"}
    for d in failing:
        plan[d] = {"passive": "infeasible"}
    summary = summarise(_store(tmp_path / "results.sqlite", config, plan, holdout))
    rows = {p["level"]: p for p in summary["pruning"]}
    assert rows["geometric"]["recall"] == 0.75 and rows["geometric"]["recall_n"] == 4
    assert rows["geometric"]["recall_basis"] == "every design"
    assert rows["geometric"]["thrown_away"] == [working[2]]
    assert rows["kinematic"]["recall"] == 0.5
    assert rows["kinematic"]["thrown_away"] == sorted(working[2:])
    assert rows["geometric"]["n"] == len(holdout)  # precision's basis
    assert rows["geometric"]["precision"] == 0.0
    pipes = {tuple(p["rungs"]): p for p in summary["pipelines"]}
    both = pipes[("geometric", "kinematic", "passive")]
    assert both["recall"] == 0.5 and both["recall_n"] == 4 and both["n"] == len(holdout)
    assert both["thrown_away"] == sorted(working[2:])
    assert pipes[("passive",)]["recall"] == 1.0
    assert summary["thrown_away"] is None  # every design got its verdict
    text = summary_table(summary)
    assert f"designs that work that kinematic would have thrown away: {working[2]}, " in text
    assert "(2 of 4 that work, every design)" in text
    page = "".join(thrown_away_parts(summary))
    assert f"kinematic: {working[2]}, {working[3]} (of 4 designs that work, every design)" in page


def test_a_ladder_that_prunes_below_the_verdict_measures_recall_on_the_holdout_only(
    tmp_path: Path,
) -> None:
    """The paper's order: geometric prunes, then the verdict. Outside the holdout only the
    designs geometric kept have a verdict (all of which pass geometric: recall there would
    read 1 whatever the truth), so recall rests on the holdout, and the designs geometric
    stopped outside it are counted, with an estimate of how many work."""
    ladder = [{**GEOMETRIC, "prunes": True}, {"level": "passive"}]
    config = _config(ladder, count=10, fraction=0.4)
    holdout = sorted(_holdout_of(config))
    rest = [d for d in range(10) if d not in holdout]
    plan = {d: {"geometric": "feasible", "passive": "feasible"} for d in rest[:2]}
    plan.update({d: {"geometric": "unknown"} for d in rest[2:]})  # 4 stopped, no verdict
    plan[holdout[0]] = {"geometric": "unknown", "passive": "feasible"}  # works, stopped
    plan[holdout[1]] = {"geometric": "unknown", "passive": "infeasible"}
    plan[holdout[2]] = {"geometric": "feasible", "passive": "feasible"}
    plan[holdout[3]] = {"geometric": "feasible", "passive": "infeasible"}
    summary = summarise(_store(tmp_path / "results.sqlite", config, plan, set(holdout)))
    row = summary["pruning"][0]
    assert row["recall_basis"] == "the holdout" and row["recall_n"] == 2
    assert row["recall"] == 0.5 and row["thrown_away"] == [holdout[0]]
    lost = summary["thrown_away"]
    assert lost["pruned"] == 4 and lost["holdout_pruned"] == 2
    assert lost["holdout_pruned_working"] == [holdout[0]]
    assert lost["estimate"] == pytest.approx(2.0)  # 4 stopped x 1 of 2
    low, high = lost["ci"]
    assert 0.0 < low < 2.0 < high < 4.0
    assert "an estimate from the holdout" in summary_table(summary)
    assert "an estimate from the holdout" in "".join(thrown_away_parts(summary))


def test_a_database_of_an_older_version_summarises_and_resumes(tmp_path: Path) -> None:
    """Before ``unknown`` and ``prunes`` existed: a planning level stored "not found within
    budget" as ``infeasible``, the config had no ``prunes`` (every planning rung pruned) and
    the evaluations table's CHECK knew three statuses. Its summary reads that infeasible as
    unknown and measures recall where the old pruning could not bias it; opened to write,
    the table accepts ``unknown`` and keeps its rows."""
    config = config_from_dict(PASSIVE_FIRST)
    holdout = _holdout_of(config)
    d = min(set(range(8)) - holdout)
    path = _store(
        tmp_path / "results.sqlite",
        config,
        {d: {"passive": "feasible", "geometric": "infeasible"}},
        holdout,
    )
    db = sqlite3.connect(path)
    with db:
        old = json.loads(db.execute("SELECT value FROM meta WHERE key = 'config'").fetchone()[0])
        for rung in old["ladder"]:
            rung.pop("prunes", None)
        db.execute("UPDATE meta SET value = ? WHERE key = 'config'", (json.dumps(old),))
    sql = db.execute("SELECT sql FROM sqlite_master WHERE name = 'evaluations'").fetchone()[0]
    rows = db.execute("SELECT * FROM evaluations").fetchall()
    db.executescript(
        "ALTER TABLE evaluations RENAME TO e; "
        + sql.replace("'infeasible', 'unknown',", "'infeasible',")
        + "; INSERT INTO evaluations SELECT * FROM e; DROP TABLE e;"
    )
    db.close()
    summary = summarise(path)
    geometric = next(lv for lv in summary["levels"] if lv["level"] == "geometric")
    assert (geometric["infeasible"], geometric["unknown"]) == (0, 1)
    rows_by_level = {p["level"]: p for p in summary["pruning"]}
    assert rows_by_level["geometric"]["thrown_away"] == [d]  # right above the verdict
    assert rows_by_level["kinematic"]["recall_basis"] == "the holdout"  # geometric pruned
    db = results_db.connect(path)
    try:
        results_db.record(db, fake_result(d, "kinematic", "unknown", 1.0), 2, 1)
        stored = db.execute("SELECT COUNT(*) FROM evaluations").fetchone()[0]
    finally:
        db.close()
    assert stored == len(rows) + 1
