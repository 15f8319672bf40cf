"""A tiny comparison end to end: one design at two levels from both entries, two planners,
a small budget in propagations; the report's files, OMPL's logs and Planner Arena's database
with its progress table, and the same runs on a second run (budgets in counts)."""

from __future__ import annotations

import json
import sqlite3

import pytest

from experiments.planner_comparison.report import text_table
from experiments.planner_comparison.run import compare
from experiments.planner_comparison.suite import suite_from_dict

TINY = {
    "name": "tiny",
    "designs": [{"preset": "table3"}],
    "levels": ["geometric", "dynamic"],
    "planners": ["rrt", "kpiece"],
    "runs": 2,
    "budgets": {"geometric": 400, "dynamic": 120},
    "bootstrap": 50,
    "progress_samples": 4,
}


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    out = tmp_path_factory.mktemp("tiny")
    return compare(suite_from_dict(TINY), out, workers=1, quiet=True), out


def test_the_report_files_and_every_problem_planned(tiny) -> None:
    report, out = tiny
    for name in ("report.md", "report.html", "report.json", "figures/dynamic.png"):
        assert (out / name).is_file(), name
    assert report["cost"]["problems_planned"] == 4  # 2 levels x 2 entries
    assert report["cost"]["runs"] == 4 * 2 * 2
    assert json.loads((out / "report.json").read_text())["levels"].keys() == {
        "geometric",
        "dynamic",
    }
    assert "RRT" in text_table(report) and "KPIECE1" in text_table(report)


def test_the_budget_bounds_every_run(tiny) -> None:
    report, _ = tiny
    for p in report["problems"]:
        for planner in p["planners"].values():
            budget = TINY["budgets"][p["level"]]
            assert planner["propagations"] <= planner["runs"] * (budget + 60)  # one iteration over


def test_planner_arenas_database_has_the_progress_and_the_budget_as_time_limit(tiny) -> None:
    _, out = tiny
    db = sqlite3.connect(out / "ompl" / "benchmark.db")
    limits = dict(db.execute("SELECT name, timelimit FROM experiments").fetchall())
    assert limits == {
        f"tiny/table3/{level}/{entry}": TINY["budgets"][level]
        for level in TINY["levels"]
        for entry in ("heavy_leading", "heavy_trailing")
    }
    units = {u for (u,) in db.execute("SELECT time_unit FROM experiments")}
    assert units == {"propagations"}
    columns = [c[1] for c in db.execute("PRAGMA table_info(progress)")]
    assert {"time", "propagations", "tree_size", "best_goal_distance"} <= set(columns)
    rows = db.execute(
        "SELECT COUNT(DISTINCT p.runid), MAX(p.time) FROM progress p JOIN runs r ON p.runid = r.id"
    ).fetchone()
    assert rows[0] == 16  # every run has its progress
    assert rows[1] <= max(TINY["budgets"].values()) + 60
