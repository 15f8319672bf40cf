"""The comparison's report data (plain dicts, the JSON's content) from the runs of every
problem: per level, each planner's solved fraction with its Wilson interval, its ECDF of
propagations to solve, the performance profiles and the best planner by their area with a
bootstrap interval, and the problems no planner solved; problems known to be unsolvable
(:mod:`.unsolvable`) are listed and not counted against any planner."""

from __future__ import annotations

import statistics
from typing import Any

import numpy as np

from experiments.planner_comparison import profiles
from experiments.planner_comparison.unsolvable import OPEN, PROVEN, resolve
from experiments.proportions import wilson_interval

TAU_STEPS = 8  # profile points per doubling of tau


def problem_key(problem: dict[str, Any]) -> str:
    """``design/level/entry``: the problem's name (OMPL's experiment, Planner Arena's
    problem)."""
    return f"{problem['design']}/{problem['level']}/{problem['entry']}"


def summarise(
    suite: dict[str, Any],
    planners: list[dict[str, str]],
    problems: list[dict[str, Any]],
) -> dict[str, Any]:
    """The report's data. ``planners``: ``{"name", "label", "about"}`` in the suite's order;
    ``problems``: ``{"design", "level", "entry", "status", "reason", "runs"}`` with ``runs``
    the planned runs (None: not planned) and ``status`` the necessary conditions' word for
    the entry before any planning (:func:`.unsolvable.entry_statuses`)."""
    problems = _resolved(problems)
    labels = [p["label"] for p in planners]
    rows = [_problem_row(p, labels) for p in problems]
    levels = {}
    for level in suite["levels"]:
        mine = [r for r in rows if r["level"] == level]
        levels[level] = _level(mine, labels, suite)
    contradictions = [problem_key(r) for r in rows if r["status"] == PROVEN and r["solved_by"]]
    return {
        "suite": suite,
        "planners": planners,
        "problems": rows,
        "levels": levels,
        "contradictions": contradictions,
    }


def _resolved(problems: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The statuses with the sliced test's pairs told apart by what the planners solved."""
    out = []
    by_design: dict[str, list[dict[str, Any]]] = {}
    for p in problems:
        by_design.setdefault(p["design"], []).append(p)
    for items in by_design.values():
        solved = {p["entry"] for p in items if p["runs"] and any(r["solved"] for r in p["runs"])}
        statuses = {p["entry"]: (p["status"], p["reason"]) for p in items}
        final = resolve(statuses, solved)
        for p in items:
            status, reason = final[p["entry"]]
            out.append({**p, "status": status, "reason": reason})
    return out


def _problem_row(p: dict[str, Any], labels: list[str]) -> dict[str, Any]:
    per: dict[str, Any] = {}
    for label in labels:
        runs = [r for r in (p["runs"] or []) if r["planner"] == label]
        solved = [r for r in runs if r["solved"]]
        cost = profiles.cost_to_solve(runs) if runs else float("inf")
        exits = [r["exit_time_s"] for r in solved if r.get("exit_time_s") is not None]
        per[label] = {
            "runs": len(runs),
            "solved": len(solved),
            "cost": cost if np.isfinite(cost) else None,
            "solved_propagations": [r["propagations"] for r in solved],
            "median_propagations_solved": _median([r["propagations"] for r in solved]),
            "median_exit_time_s": _median(exits),
            "propagations": sum(r["propagations"] for r in runs),
        }
    return {
        "name": problem_key(p),
        "design": p["design"],
        "level": p["level"],
        "entry": p["entry"],
        "status": p["status"],
        "reason": p["reason"],
        "planned": p["runs"] is not None,
        "counted": p["status"] == OPEN and p["runs"] is not None,
        "solved_by": [label for label in labels if per[label]["solved"] > 0],
        "planners": per,
    }


def _median(values: list[float]) -> float | None:
    return float(statistics.median(values)) if values else None


def _level(rows: list[dict[str, Any]], labels: list[str], suite: dict[str, Any]) -> dict[str, Any]:
    counted = [r for r in rows if r["counted"]]
    excluded = [
        {
            "problem": r["name"],
            "status": r["status"],
            "reason": r["reason"],
            "planned": r["planned"],
        }
        for r in rows
        if not r["counted"]
    ]
    unsolved = [r["name"] for r in counted if not r["solved_by"]]
    planners = {}
    ecdfs = {}
    for label in labels:
        k = sum(r["planners"][label]["solved"] for r in counted)
        n = sum(r["planners"][label]["runs"] for r in counted)
        lo, hi = wilson_interval(k, n)
        exits = [
            r["planners"][label]["median_exit_time_s"]
            for r in counted
            if r["planners"][label]["median_exit_time_s"] is not None
        ]
        planners[label] = {
            "solved_runs": k,
            "runs": n,
            "fraction": k / n if n else None,
            "wilson95": [lo, hi],
            "problems_solved": sum(1 for r in counted if r["planners"][label]["solved"] > 0),
            "median_exit_time_s": _median(exits),
        }
    solved_costs = _solved_costs(rows, labels)
    for label in labels:
        xs, ys = profiles.ecdf(solved_costs[label], max(planners[label]["runs"], 1))
        ecdfs[label] = {"x": xs, "y": ys, "runs": planners[label]["runs"]}
    profiled = [r for r in counted if r["solved_by"]]
    level = {
        "problems": len(rows),
        "counted": len(counted),
        "excluded": excluded,
        "unsolved_by_all": unsolved,
        "planners": planners,
        "ecdf": ecdfs,
        "profile": None,
        "best": None,
    }
    if not profiled:
        return level
    costs = np.array(
        [
            [
                r["planners"][label]["cost"] if r["planners"][label]["cost"] is not None else np.inf
                for label in labels
            ]
            for r in profiled
        ]
    )
    ratios = profiles.ratio_matrix(costs)
    top = profiles.horizon(ratios)
    taus = [2.0 ** (k / TAU_STEPS) for k in range(int(np.ceil(top * TAU_STEPS)) + 1)]
    rho = profiles.profile(ratios, taus)
    boot = profiles.bootstrap_best(ratios, top, int(suite["bootstrap"]), int(suite["seed"]))
    order = sorted(range(len(labels)), key=lambda j: (-boot["area"][j], labels[j]))
    best = order[0]
    level["profile"] = {
        "problems": [r["name"] for r in profiled],
        "cost": "expected propagations to the first success with restarts (all runs' "
        "propagations over the runs solved)",
        "log2_tau_max": top,
        "taus": taus,
        "rho": {label: rho[:, j].tolist() for j, label in enumerate(labels)},
        "ratios": {label: [_ratio(x) for x in ratios[:, j]] for j, label in enumerate(labels)},
    }
    level["best"] = {
        "planner": labels[best],
        "area": {
            label: {
                "area": float(boot["area"][j]),
                "interval95": [float(boot["low"][j]), float(boot["high"][j])],
                "best_share": float(boot["best_share"][j]),
            }
            for j, label in enumerate(labels)
        },
        "ranking": [labels[j] for j in order],
        "resamples": int(suite["bootstrap"]),
        "seed": int(suite["seed"]),
    }
    return level


def _ratio(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def _solved_costs(rows: list[dict[str, Any]], labels: list[str]) -> dict[str, list[float]]:
    """Per planner, the propagations of each run that solved a counted problem."""
    out: dict[str, list[float]] = {label: [] for label in labels}
    for r in rows:
        if not r["counted"]:
            continue
        for label in labels:
            out[label].extend(r["planners"][label]["solved_propagations"])
    return out
