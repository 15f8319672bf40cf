"""A level's problem through OMPL's Benchmark: budgets in propagations, our own run
properties in OMPL's log, and a log that OMPL's own reader accepts."""

from __future__ import annotations

import contextlib
import functools
import io
import math
import sqlite3

import pytest
from ompl import _benchmark_statistics as obs

from feeders.design import PRESETS
from feeders.feeder import build_feeder
from planners.benchmark import Budget, benchmark_problem
from planners.plan import PlannerSettings


@functools.cache
def _scene():
    return build_feeder(PRESETS["table3"], name="table3")


def _bench(budget: Budget, planners=("rrt", "kpiece"), runs: int = 2, seed: int = 3):
    return benchmark_problem(
        _scene(),
        "kinematic",
        "heavy_leading",
        list(planners),
        runs,
        budget,
        seed,
        experiment="test",
        parameters={"a": 1.25, "design_id": 7, "level": "kinematic"},
    )


def test_a_propagation_budget_gives_the_same_runs_every_time() -> None:
    first, second = _bench(Budget(60.0, 2500)), _bench(Budget(60.0, 2500))
    keys = ("planner", "run", "seed", "solved", "tree_size", "propagations", "validity_checks")
    assert [[r[k] for k in keys] for r in first.runs] == [[r[k] for k in keys] for r in second.runs]


def test_a_propagation_budget_stops_a_run_within_one_planner_iteration_of_it() -> None:
    budget = 300  # far too few to reach the goal
    result = _bench(Budget(60.0, budget))
    # one iteration propagates a control for at most max_steps steps (KPIECE1 may try a few
    # controls per iteration): the overshoot is small, and a run never stops short of it
    most = PlannerSettings().max_steps * 3
    for run in result.runs:
        assert not run["solved"]
        assert budget <= run["propagations"] <= budget + most
        assert run["time_s"] < 30.0


def test_runs_are_seeded_by_run_index_so_planners_start_alike() -> None:
    result = _bench(Budget(1.0), runs=3, seed=11)
    assert [r["seed"] for r in result.runs] == [11, 12, 13, 11, 12, 13]
    assert [r["run"] for r in result.runs] == [0, 1, 2, 0, 1, 2]


def test_the_log_opens_with_ompls_reader_with_our_properties_as_columns(tmp_path) -> None:
    result = _bench(Budget(60.0, 2500))
    log = tmp_path / "run.log"
    log.write_text(result.log)
    db_path = tmp_path / "bench.db"
    with contextlib.redirect_stdout(io.StringIO()):
        obs.readBenchmarkLog(str(db_path), [str(log)], False)
    db = sqlite3.connect(db_path)
    experiments = [c[1] for c in db.execute("PRAGMA table_info(experiments)")]
    assert {"a", "design_id", "level"} <= set(experiments)
    assert db.execute("SELECT a, design_id, level FROM experiments").fetchone() == (
        1.25,
        7,
        "kinematic",
    )
    rows = db.execute(
        "SELECT exact_solution, propagations, validity_checks, graph_states, exit_time, time "
        "FROM runs ORDER BY id"
    ).fetchall()
    assert len(rows) == len(result.runs)
    for row, run in zip(rows, result.runs, strict=True):
        exact, propagations, checks, states, exit_time, time_s = row
        assert (exact, propagations, checks) == (
            int(run["solved"]),
            run["propagations"],
            run["validity_checks"],
        )
        # the wrapped planner's tree is its inner planner's, not the wrapper's two states
        assert states == run["tree_size"] > 2
        assert time_s == pytest.approx(run["time_s"], rel=1e-5)
        if run["solved"]:
            assert exit_time == pytest.approx(run["exit_time_s"])
            assert exit_time > 0
        else:
            assert exit_time is None


def test_a_time_budget_is_respected() -> None:
    result = _bench(Budget(0.2), planners=("kpiece",), runs=2)
    for run in result.runs:
        assert run["time_s"] <= 0.2 + 0.2  # OMPL checks its clock between iterations
        assert not math.isnan(run["time_s"])


def test_bad_arguments_name_what_is_wrong() -> None:
    with pytest.raises(ValueError, match="unknown planner 'prm'"):
        _bench(Budget(1.0), planners=("prm",))
    with pytest.raises(ValueError, match="runs = 0"):
        _bench(Budget(1.0), runs=0)
    with pytest.raises(ValueError, match="budget propagations = 0"):
        Budget(1.0, 0)
    with pytest.raises(ValueError, match="budget time = -1"):
        Budget(-1.0)


def test_nothing_is_written_to_the_working_directory(tmp_path, monkeypatch) -> None:
    """OMPL's Benchmark saves an ompl_<host>_<date>.console file per experiment unless told."""
    monkeypatch.chdir(tmp_path)
    _bench(Budget(0.1), planners=("rrt",), runs=1)
    assert list(tmp_path.iterdir()) == []
