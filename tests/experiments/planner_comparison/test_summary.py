"""The report's data from runs: solved fractions with Wilson intervals over the problems that
count, problems known to be unsolvable left out (and a sliced pair told apart by what was
solved), the best planner, and the JSON's fields."""

from __future__ import annotations

import json

import pytest

from experiments.planner_comparison.summary import summarise
from experiments.planner_comparison.unsolvable import ONE_OF_TWO, OPEN, PROVEN
from experiments.proportions import wilson_interval

PLANNERS = [
    {"name": "rrt", "label": "RRT", "about": "a"},
    {"name": "kpiece", "label": "KPIECE1", "about": "b"},
]
SUITE = {"levels": ["dynamic"], "bootstrap": 200, "seed": 1, "name": "t", "runs": 2}


def _runs(solved: dict[str, list[int | None]]) -> list[dict]:
    """Runs per planner label: a number of propagations that solved, or None (unsolved,
    1000 propagations spent)."""
    return [
        {
            "planner": label,
            "solved": p is not None,
            "propagations": 1000 if p is None else p,
            "exit_time_s": None if p is None else 2.0,
        }
        for label, spent in solved.items()
        for p in spent
    ]


NONE = {"RRT": [None, None], "KPIECE1": [None, None]}  # four unsolved runs


def _problem(design, entry, status, runs, reason="r"):
    return {
        "design": design,
        "level": "dynamic",
        "entry": entry,
        "status": status,
        "reason": reason,
        "runs": runs,
    }


PROBLEMS = [
    _problem("a", "heavy_leading", OPEN, _runs({"RRT": [100, 300], "KPIECE1": [200, None]})),
    _problem("a", "heavy_trailing", OPEN, _runs({"RRT": [None, None], "KPIECE1": [50, 50]})),
    _problem("b", "heavy_leading", OPEN, _runs(NONE)),
    # proven unsolvable (turn test): not planned, so not counted
    _problem("b", "heavy_trailing", PROVEN, None),
    # the sliced test: one of the pair is unsolvable; c's leading entry was solved
    _problem("c", "heavy_leading", ONE_OF_TWO, _runs({"RRT": [80, None], "KPIECE1": [None, None]})),
    _problem("c", "heavy_trailing", ONE_OF_TWO, _runs(NONE)),
    # the sliced test, neither entry solved: both left out
    _problem("d", "heavy_leading", ONE_OF_TWO, _runs(NONE)),
    _problem("d", "heavy_trailing", ONE_OF_TWO, _runs(NONE)),
]


@pytest.fixture(scope="module")
def report() -> dict:
    return summarise(SUITE, PLANNERS, PROBLEMS)


def test_a_sliced_pair_with_one_entry_solved_proves_the_other_unsolvable(report) -> None:
    status = {r["name"]: r["status"] for r in report["problems"]}
    assert status["c/dynamic/heavy_leading"] == OPEN
    assert status["c/dynamic/heavy_trailing"] == PROVEN
    assert status["d/dynamic/heavy_leading"] == ONE_OF_TWO  # still not told apart
    assert status["b/dynamic/heavy_trailing"] == PROVEN


def test_unsolvable_problems_are_listed_and_not_counted(report) -> None:
    level = report["levels"]["dynamic"]
    assert level["counted"] == 4  # a x 2, b leading, c leading
    excluded = {e["problem"] for e in level["excluded"]}
    assert excluded == {
        "b/dynamic/heavy_trailing",
        "c/dynamic/heavy_trailing",
        "d/dynamic/heavy_leading",
        "d/dynamic/heavy_trailing",
    }
    assert level["unsolved_by_all"] == ["b/dynamic/heavy_leading"]


def test_solved_fractions_are_runs_on_counted_problems_with_wilson_intervals(report) -> None:
    planners = report["levels"]["dynamic"]["planners"]
    # RRT: a-leading 2, a-trailing 0, b-leading 0, c-leading 1 of 8 runs
    assert (planners["RRT"]["solved_runs"], planners["RRT"]["runs"]) == (3, 8)
    assert planners["RRT"]["wilson95"] == list(wilson_interval(3, 8))
    assert (planners["KPIECE1"]["solved_runs"], planners["KPIECE1"]["runs"]) == (3, 8)
    assert planners["KPIECE1"]["wilson95"] == list(wilson_interval(3, 8))


def test_the_profile_ranks_by_the_cost_to_solve(report) -> None:
    level = report["levels"]["dynamic"]
    # costs: a-leading RRT 200, KPIECE1 1200; a-trailing KPIECE1 50; c-leading RRT 1080
    assert level["profile"]["problems"] == [
        "a/dynamic/heavy_leading",
        "a/dynamic/heavy_trailing",
        "c/dynamic/heavy_leading",
    ]
    assert level["profile"]["ratios"]["RRT"] == [1.0, None, 1.0]
    assert level["profile"]["ratios"]["KPIECE1"] == [6.0, 1.0, None]
    best = level["best"]
    assert best["planner"] == "RRT"  # best on 2 of 3 against 1 of 3
    area = best["area"]["RRT"]
    assert area["interval95"][0] <= area["area"] <= area["interval95"][1]


def test_the_report_is_json_with_its_fields(report) -> None:
    text = json.dumps(report, allow_nan=False)  # no NaN or inf anywhere
    data = json.loads(text)
    assert set(data) >= {"suite", "planners", "problems", "levels", "contradictions"}
    level = data["levels"]["dynamic"]
    assert set(level) == {
        "problems",
        "counted",
        "excluded",
        "unsolved_by_all",
        "planners",
        "ecdf",
        "profile",
        "best",
    }
    assert set(level["planners"]["RRT"]) == {
        "solved_runs",
        "runs",
        "fraction",
        "wilson95",
        "problems_solved",
        "median_exit_time_s",
    }
    assert set(level["profile"]) >= {"taus", "rho", "ratios", "problems", "log2_tau_max"}
    problem = data["problems"][0]
    assert set(problem) >= {"name", "status", "reason", "planned", "counted", "solved_by"}
    assert data["contradictions"] == []


def test_a_planner_solving_a_proven_unsolvable_problem_is_a_contradiction() -> None:
    problems = [
        _problem("e", "heavy_leading", OPEN, _runs({"RRT": [10], "KPIECE1": [None]})),
        _problem("e", "heavy_trailing", PROVEN, _runs({"RRT": [10], "KPIECE1": [None]})),
    ]
    data = summarise(SUITE, PLANNERS, problems)
    assert data["contradictions"] == ["e/dynamic/heavy_trailing"]
