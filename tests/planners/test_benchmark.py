"""A level's problem through OMPL's Benchmark: budgets in propagations, our own run
properties in OMPL's log, and a log that OMPL's own reader accepts."""

from __future__ import annotations

import contextlib
import doctest
import functools
import io
import math
import sqlite3

import pytest
from ompl import _benchmark_statistics as obs
from ompl import base as ob
from ompl import control as oc

from feeders.design import PRESETS
from feeders.feeder import build_feeder
from planners.benchmark import Budget, benchmark_control_problem, benchmark_problem
from planners.plan import PlannerSettings, control_problem


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
    result = _bench(Budget(60.0, 500), runs=3, seed=11)
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


def test_a_time_budget_stops_a_run_whatever_its_propagation_budget() -> None:
    """The time stops a run that the count would not (no upper bound on the time is
    asserted: OMPL checks its clock between iterations, and an iteration of a loaded machine
    takes as long as it takes; a bound of 0.4 s failed under load 8 on 2 cores)."""
    budget = Budget(0.2, 10**9)
    result = _bench(budget, planners=("kpiece",), runs=2)
    for run in result.runs:
        assert not math.isnan(run["time_s"])
        assert run["solved"] or run["time_s"] >= budget.time_s
        assert run["propagations"] < 10**9


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
    _bench(Budget(60.0, 200), planners=("rrt",), runs=1)
    assert list(tmp_path.iterdir()) == []


def _rrt_with_goal_bias(si: oc.SpaceInformation) -> ob.Planner:
    planner = oc.RRT(si)
    planner.setGoalBias(0.2)
    return planner


class _Delegating(ob.Planner):
    """A researcher's own planner written in Python: here it hands the search to KPIECE1."""

    def __init__(self, si: oc.SpaceInformation) -> None:
        super().__init__(si, "MyPlanner")
        self.inner = oc.KPIECE1(si)

    def setup(self) -> None:
        super().setup()
        self.inner.setProblemDefinition(self.getProblemDefinition())
        self.inner.setup()

    def clear(self) -> None:
        super().clear()
        self.inner.clear()

    def solve(self, ptc):
        return self.inner.solve(ptc)

    def getPlannerData(self, data) -> None:
        self.inner.getPlannerData(data)


def _read_db(tmp_path, log: str) -> sqlite3.Connection:
    path = tmp_path / "run.log"
    path.write_text(log)
    db_path = tmp_path / "bench.db"
    db_path.unlink(missing_ok=True)
    with contextlib.redirect_stdout(io.StringIO()):
        obs.readBenchmarkLog(str(db_path), [str(path)], False)
    return sqlite3.connect(db_path)


def _settings(db: sqlite3.Connection) -> dict[str, dict[str, str]]:
    """plannerConfigs as {planner name: {parameter: value}} (OMPL's reader stores a planner's
    common properties as 'name = value\\n;' pairs)."""
    out: dict[str, dict[str, str]] = {}
    for name, settings in db.execute("SELECT name, settings FROM plannerConfigs"):
        pairs = [p.strip().split(" = ", 1) for p in settings.split(";") if p.strip()]
        out[name] = dict(pairs)
    return out


def test_planners_may_be_factories_named_in_the_log_by_their_own_name(tmp_path) -> None:
    result = _bench(Budget(60.0, 1500), planners=(_rrt_with_goal_bias, _Delegating, "est"))
    assert [r["planner"] for r in result.runs] == ["RRT"] * 2 + ["MyPlanner"] * 2 + ["EST"] * 2
    db = _read_db(tmp_path, result.log)
    assert set(_settings(db)) == {"control_RRT", "control_MyPlanner", "control_EST"}
    # the Python planner searched: its tree is its inner KPIECE1's
    assert all(r["tree_size"] > 2 for r in result.runs if r["planner"] == "MyPlanner")


def test_the_planners_own_parameters_are_in_plannerconfigs_with_their_values(tmp_path) -> None:
    result = _bench(Budget(60.0, 600), planners=(_rrt_with_goal_bias, "kpiece", "est"), runs=1)
    settings = _settings(_read_db(tmp_path, result.log))
    rrt, kpiece, est = (settings[f"control_{n}"] for n in ("RRT", "KPIECE1", "EST"))
    assert float(rrt["goal_bias"]) == 0.2  # the factory's, not RRT's default 0.05
    assert rrt["intermediate_states"] == "0"
    assert float(kpiece["goal_bias"]) == 0.05
    assert float(kpiece["border_fraction"]) == 0.8
    assert int(kpiece["max_close_samples"]) == 30
    assert float(kpiece["bad_score_factor"]) == 0.45
    assert float(kpiece["good_score_factor"]) == 0.9
    # EST's range as set up for this space (0 until setup), as OMPL's own Benchmark logs it
    assert float(est["range"]) > 0
    # the space information's settings stay beside them
    for planner in (rrt, kpiece, est):
        assert float(planner["propagation_step_size"]) == PlannerSettings().step


def test_two_planners_of_one_name_are_refused() -> None:
    with pytest.raises(ValueError, match="two planners named 'RRT'"):
        _bench(Budget(1.0, 100), planners=("rrt", _rrt_with_goal_bias))


def test_a_factory_must_return_an_ompl_planner() -> None:
    with pytest.raises(TypeError, match="planner factory returned int"):
        _bench(Budget(1.0, 100), planners=(lambda si: 3,))


def test_a_problem_built_by_the_user_is_benchmarked_as_built(tmp_path) -> None:
    """benchmark_problem builds the problem and hands it to benchmark_control_problem: the
    same arguments give the same runs; a problem changed before benchmarking is benchmarked
    with its change."""
    budget = Budget(60.0, 1500)
    problem = control_problem(_scene(), "kinematic", "heavy_leading", 3, count=True)
    built = benchmark_control_problem(problem, ["rrt", "kpiece"], 2, budget, 3, "test")
    direct = _bench(budget)
    keys = ("planner", "run", "seed", "solved", "tree_size", "propagations", "validity_checks")
    assert [[r[k] for k in keys] for r in built.runs] == [[r[k] for k in keys] for r in direct.runs]

    changed = control_problem(_scene(), "kinematic", "heavy_leading", 3, count=True)
    changed.si.setMinMaxControlDuration(1, 5)
    result = benchmark_control_problem(changed, ["rrt"], 1, budget, 3, "test")
    assert _settings(_read_db(tmp_path, result.log))["control_RRT"]["max_control_duration"] == "5"


def test_a_problem_without_counts_is_refused() -> None:
    problem = control_problem(_scene(), "kinematic", "heavy_leading", 3)
    with pytest.raises(ValueError, match="count=True"):
        benchmark_control_problem(problem, ["rrt"], 1, Budget(1.0, 100), 3, "test")


def test_the_docstring_examples_run() -> None:
    import planners.benchmark

    failures, tried = doctest.testmod(planners.benchmark)
    assert tried >= 6 and failures == 0


def test_solved_is_as_ompls_benchmark_writes_it_with_exactness_its_own_column(tmp_path) -> None:
    """OMPL's Benchmark (2.0.1, any planner, wrapped or not) writes "solved" = the setup has an
    exact solution path and keeps an approximate one in "status" (5, "Approximate solution")
    and "approximate solution": a plain oc.EST stopped early logs solved 0, status 5,
    approximate solution 1. The log keeps that convention, so the database compares with any
    other OMPL database; our "exact solution" column says the same as "solved", by name."""
    short, long = _bench(Budget(60.0, 300), runs=1), _bench(Budget(60.0, 2500), runs=2)
    kinds = set()
    for k, result in enumerate((short, long)):
        (tmp_path / str(k)).mkdir()
        db = _read_db(tmp_path / str(k), result.log)
        enum = dict(db.execute("SELECT value, description FROM enums WHERE name = 'status'"))
        assert (enum[5], enum[6]) == ("Approximate solution", "Exact solution")
        rows = db.execute(
            "SELECT solved, exact_solution, approximate_solution, status FROM runs ORDER BY id"
        ).fetchall()
        for (solved, exact, approximate, status), run in zip(rows, result.runs, strict=True):
            assert solved == exact == int(run["solved"]) == int(status == 6)
            assert approximate == int(run["approximate"]) == int(status == 5)
            kinds.add(status)
    assert {5, 6} <= kinds  # both kinds of ending were seen
