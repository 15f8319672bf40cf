"""A sweep's OMPL database as Planner Arena sees it: one problem per design, level and entry,
every planner's own parameters in its configuration, ``runs`` runs per planner per problem,
and "solved" as OMPL's Benchmark writes it.

The database is made the repository's way (``run_sweep``, then ``export_ompl`` through OMPL's
own log reader) from a small sweep whose budgets are counts of propagations, so it is the same
on any machine. It is read twice: with Planner Arena's own loader
(``plannerarena.database.load_database``, when plannerarena is installed: ``pip install
plannerarena``) and directly with sqlite3 (always).
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

from experiments.sweep.config import config_from_dict
from experiments.sweep.job import problem_name
from experiments.sweep.ladder import export_ompl, run_sweep

RUNS = 2
SMALL = {
    "name": "arena",
    "designs": {"count": 3, "seed": 1},
    "feeder": {"inputs": {"max_force": 10.0, "max_torque": 2.0}},
    "ladder": [
        {
            "level": "geometric",
            "planners": ["rrt", "kpiece", "est"],
            "runs": RUNS,
            "budget": {"propagations": 4000},
        },
        {"level": "kinematic", "planners": ["rrt"], "runs": RUNS, "budget": {"propagations": 400}},
    ],
    "holdout": {"fraction": 1.0, "seed": 7},  # every design climbs every rung
    "workers": 1,
    "max_attempts": 1,
}

# What OMPL 2's planners declare (their params()), beside the space information's settings.
OWN_PARAMETERS = {
    "RRT": {"goal_bias", "intermediate_states"},
    "KPIECE1": {
        "goal_bias",
        "border_fraction",
        "max_close_samples",
        "bad_score_factor",
        "good_score_factor",
    },
    "EST": {"goal_bias", "range"},
}


@pytest.fixture(scope="module")
def sweep(tmp_path_factory) -> tuple[Path, Path]:
    """(results database, OMPL database) of the small sweep."""
    out = tmp_path_factory.mktemp("arena")
    results = run_sweep(config_from_dict(SMALL), out)
    return results, export_ompl(results, out / "ompl")


def _entries(results: Path) -> set[str]:
    """The problem name of every (design, level, entry) the sweep planned."""
    db = sqlite3.connect(results)
    names = set()
    for design_id, level, leading, trailing in db.execute(
        "SELECT design_id, level, heavy_leading, heavy_trailing FROM evaluations"
    ):
        for orientation, flag in (("heavy_leading", leading), ("heavy_trailing", trailing)):
            if flag is not None:
                names.add(problem_name("arena", design_id, level, orientation))
    db.close()
    return names


def _parameters(settings: str) -> dict[str, str]:
    """OMPL's reader stores a planner's common properties as 'name = value\\n;' pairs."""
    pairs = (p.strip().split(" = ", 1) for p in settings.split(";"))
    return {p[0]: p[1] for p in pairs if len(p) == 2}


def test_the_database_has_one_problem_per_entry_planned_and_every_planners_parameters(
    sweep,
) -> None:
    results, target = sweep
    db = sqlite3.connect(target)
    names = [name for (name,) in db.execute("SELECT name FROM experiments")]
    assert sorted(names) == sorted(_entries(results))
    assert len(names) >= 3 * 2  # each design's leading entry at both levels, at least
    assert {c for (c,) in db.execute("SELECT runcount FROM experiments")} == {RUNS}
    per_problem = db.execute(
        "SELECT e.name, p.name, COUNT(*) FROM runs r JOIN experiments e ON r.experimentid = e.id "
        "JOIN plannerConfigs p ON r.plannerid = p.id GROUP BY e.id, p.name"
    ).fetchall()
    assert {count for *_, count in per_problem} == {RUNS}
    assert {(n.split("/")[2], p) for n, p, _ in per_problem} == {
        ("geometric", "control_RRT"),
        ("geometric", "control_KPIECE1"),
        ("geometric", "control_EST"),
        ("kinematic", "control_RRT"),
    }
    for planner, settings in db.execute("SELECT name, settings FROM plannerConfigs"):
        parameters = _parameters(settings)
        own = OWN_PARAMETERS[planner.removeprefix("control_")]
        assert own <= set(parameters), planner
        assert float(parameters["goal_bias"]) == 0.05  # OMPL's default, as configured
        assert "propagation_step_size" in parameters  # the space information's, beside them
    # solved as OMPL's Benchmark writes it; exactness its own column, saying the same
    for solved, exact, approximate, status in db.execute(
        "SELECT solved, exact_solution, approximate_solution, status FROM runs"
    ):
        assert solved == exact == int(status == 6)
        assert approximate == int(status == 5)


def test_planner_arenas_own_loader_sees_the_problems_planners_and_parameters(sweep) -> None:
    pytest.importorskip("plannerarena")
    from plannerarena.database import load_database

    results, target = sweep
    data = load_database(target)
    assert sorted(data["problem_names"]) == sorted(_entries(results))
    runs = data["runs"]
    counts = runs.group_by(["experiment", "planner"]).len()["len"].to_list()
    assert set(counts) == {RUNS}
    assert {str(p) for p in runs["planner"].unique().to_list()} == set(OWN_PARAMETERS)
    configs = data["planner_configs"].select("planner", "settings").iter_rows()
    seen = set()
    for planner, settings in configs:
        assert OWN_PARAMETERS[str(planner)] <= set(_parameters(settings)), planner
        seen.add(str(planner))
    assert seen == set(OWN_PARAMETERS)
    for attribute in ("solved", "status", "exact solution", "propagations", "exit time"):
        assert attribute in data["attributes"]


# Progress (issue 40): a benchmark with progress_every records each run's progress; OMPL's
# reader puts it in the database's progress table, whose "time" counts propagations, and the
# experiment's time limit is the propagation budget.
PROGRESS_BUDGET = 600
PROGRESS_EVERY = 150
PROGRESS_RUNS = 2


@pytest.fixture(scope="module")
def progress_database(tmp_path_factory) -> Path:
    import shutil
    import subprocess
    import sys

    from feeders.design import PRESETS
    from feeders.feeder import build_feeder
    from planners.benchmark import Budget, benchmark_problem

    out = tmp_path_factory.mktemp("progress")
    result = benchmark_problem(
        build_feeder(PRESETS["table3"], name="table3"),
        "geometric",
        "heavy_leading",
        ["rrt", "kpiece"],
        runs=PROGRESS_RUNS,
        budget=Budget(60.0, PROGRESS_BUDGET),
        seed=1,
        experiment="progress/table3/geometric/heavy_leading",
        progress_every=PROGRESS_EVERY,
    )
    log = out / "run.log"
    log.write_text(result.log)
    script = Path(sys.executable).with_name("ompl_benchmark_statistics")
    command = str(script) if script.exists() else shutil.which("ompl_benchmark_statistics")
    database = out / "progress.db"
    subprocess.run([command, str(log), "-d", str(database)], check=True, stdout=subprocess.DEVNULL)
    return database


def test_the_progress_table_holds_every_runs_progress_over_propagations(
    progress_database,
) -> None:
    db = sqlite3.connect(progress_database)
    assert db.execute("SELECT timelimit, time_unit FROM experiments").fetchall() == [
        (float(PROGRESS_BUDGET), "propagations")
    ]
    columns = [c[1] for c in db.execute("PRAGMA table_info(progress)")]
    assert columns == ["runid", "time", "propagations", "tree_size", "best_goal_distance"]
    per_run = db.execute(
        "SELECT runid, COUNT(*), MIN(time), MAX(time), MAX(propagations) FROM progress "
        "GROUP BY runid"
    ).fetchall()
    assert len(per_run) == 2 * PROGRESS_RUNS
    for _, samples, first, last, spent in per_run:
        assert samples >= 2
        assert PROGRESS_EVERY <= first and last == spent  # time is the propagation count
    run_spent = dict(db.execute("SELECT id, propagations FROM runs").fetchall())
    for runid, *_, spent in per_run:
        assert spent == run_spent[runid]  # the last sample is the run's end
    for runid in run_spent:
        series = db.execute(
            "SELECT tree_size, best_goal_distance FROM progress WHERE runid = ? ORDER BY time",
            (runid,),
        ).fetchall()
        sizes = [s for s, _ in series]
        best = [d for _, d in series if d is not None]
        assert sizes == sorted(sizes)  # a tree only grows
        assert best == sorted(best, reverse=True)  # the best distance only falls


def test_planner_arenas_own_loader_reads_the_progress(progress_database) -> None:
    pytest.importorskip("plannerarena")
    from plannerarena.database import load_database

    data = load_database(progress_database)
    progress = data["progress"]
    assert {"time", "propagations", "tree size", "best goal distance"} <= set(progress.columns)
    assert progress.height >= 2 * 2 * PROGRESS_RUNS
    joined = progress.join(data["runs"].select("id", "planner"), left_on="runid", right_on="id")
    assert {str(p) for p in joined["planner"].unique().to_list()} == {"RRT", "KPIECE1"}
