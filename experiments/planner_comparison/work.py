"""One problem (design, level, entry) planned by every planner of the comparison, in a
worker: plain data in (a job dict), plain data out (the runs and OMPL's log). The worker
builds its own scene and OMPL objects; OMPL's console log is off in the pool's workers
(:func:`experiments.executors.worker.start_worker`)."""

from __future__ import annotations

import math
import time
from typing import Any

TIME_CAP_S = 600.0  # OMPL's time limit per run: only a cap, the budget is in propagations


def plan_problem(job: dict[str, Any]) -> dict[str, Any]:
    """Benchmark ``job["planners"]`` on the job's problem, ``job["runs"]`` runs each within
    ``job["budget"]`` propagations, run r seeded with ``job["seed"] + r``, progress every
    ``job["progress_every"]`` propagations: ``{"runs": [...], "log": str, "wall_s": float}``
    (:class:`planners.benchmark.BenchmarkResult`'s runs, NaN and inf as None)."""
    from experiments.planner_comparison.designs import scene_for
    from planners.benchmark import Budget, benchmark_problem

    t0 = time.perf_counter()
    scene = scene_for(job["design"], job.get("base", "."))
    result = benchmark_problem(
        scene,
        job["level"],
        job["entry"],
        list(job["planners"]),
        runs=int(job["runs"]),
        budget=Budget(TIME_CAP_S, int(job["budget"])),
        seed=int(job["seed"]),
        experiment=job["experiment"],
        parameters={"design": job["design_name"], "level": job["level"], "entry": job["entry"]},
        progress_every=int(job["progress_every"]),
    )
    return {
        "runs": [_plain(r) for r in result.runs],
        "log": result.log,
        "wall_s": time.perf_counter() - t0,
    }


def _plain(row: dict[str, Any]) -> dict[str, Any]:
    """A run's row for JSON: non-finite numbers as None, progress as lists."""
    out: dict[str, Any] = {}
    for key, value in row.items():
        if key == "progress":
            out[key] = [[int(p), int(s), _finite(d)] for p, s, d in value]
        elif isinstance(value, float):
            out[key] = _finite(value)
        else:
            out[key] = value
    return out


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None
