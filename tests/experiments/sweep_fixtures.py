"""Shared pieces of the sweep tests: a tiny config with budgets in propagations (so results
are the same on any machine and executor) and the columns that must then agree."""

from __future__ import annotations

import os
import signal
import sqlite3
from pathlib import Path

from experiments.sweep.config import SweepConfig, config_from_dict
from experiments.sweep.job import evaluate_design

TINY = {
    "name": "tiny",
    "designs": {"count": 6, "seed": 1},
    "feeder": {"inputs": {"max_force": 10.0, "max_torque": 2.0}},
    "ladder": [
        {"level": "geometric", "planners": ["rrt"], "budget": {"propagations": 20000}},
        {"level": "kinematic", "planners": ["rrt"], "budget": {"propagations": 6000}},
        {"level": "dynamic", "planners": ["rrt", "kpiece"], "budget": {"propagations": 1500}},
    ],
    "holdout": {"fraction": 0.5, "seed": 7},
    "workers": 2,
    "max_attempts": 2,
}

EVALUATION_COLUMNS = "design_id, level, rung, status, reason, heavy_leading, heavy_trailing"
RUN_COLUMNS = (
    "design_id, level, orientation, planner, run, seed, solved, approximate, tree_size, "
    "tree_edges, propagations, validity_checks, exit_time_s"
)
CRASHING_DESIGN = 2


def tiny_config(**changes) -> SweepConfig:
    return config_from_dict({**TINY, **changes})


def machine_independent_rows(path: Path) -> dict[str, list[tuple]]:
    """What a sweep with propagation budgets must reproduce exactly (not times or workers)."""
    db = sqlite3.connect(path)
    try:
        return {
            "designs": db.execute("SELECT * FROM designs ORDER BY design_id").fetchall(),
            "evaluations": db.execute(
                f"SELECT {EVALUATION_COLUMNS} FROM evaluations ORDER BY design_id, rung"
            ).fetchall(),
            "runs": db.execute(
                f"SELECT {RUN_COLUMNS} FROM runs ORDER BY design_id, level, orientation, "
                "planner, run"
            ).fetchall(),
            "quarantine": db.execute(
                "SELECT design_id, level FROM quarantine ORDER BY design_id"
            ).fetchall(),
        }
    finally:
        db.close()


def crash_on_one_design(job: dict) -> dict:
    """``evaluate_design``, except that the worker running design CRASHING_DESIGN dies
    (SIGKILL, as the OOM killer would), every time."""
    if job["design_id"] == CRASHING_DESIGN:
        os.kill(os.getpid(), signal.SIGKILL)
    return evaluate_design(job)


def fake_result(design_id: int, level: str, status: str, wall: float, verdict=None) -> dict:
    """A hand-made evaluation as a worker returns it (the leading entry's flag only)."""
    result = {
        "design_id": design_id,
        "level": level,
        "status": status,
        "reason": None,
        "orientations": {"heavy_leading": status == "feasible", "heavy_trailing": None},
        "runs": [],
        "logs": {},
        "worker": "test",
        "wall_time_s": wall,
    }
    if verdict is not None:
        result["verdict"], result["verdict_seed"] = verdict, 1
    return result


def fake_verdict(decision: str, k: int, n: int, exit_time: float | None) -> dict:
    """A hand-made verdict (``Verdict.to_dict`` shape): k of n trials succeed from both."""
    per = {"successes": k, "p": k / n, "interval": [0.0, 1.0], "mean_exit_time_s": exit_time}
    return {
        "decision": decision,
        "works": decision == "works",
        "target": 0.9,
        "drops": n,
        "orientations": {"heavy_leading": per, "heavy_trailing": per},
        "both": {"successes": k, "p": k / n, "interval": [k / n - 0.1, 1.0]},
        "transitions": {},
        "wall_time_s": 0.1,
    }
