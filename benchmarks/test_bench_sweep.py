"""pytest-benchmark timings of the main job's per-design work: measure, never assert.

Run explicitly::

    python -m pytest benchmarks/test_bench_sweep.py -q

(a)/(b): OMPL's callbacks (validity check + propagation of one step) with and without the
counting that the propagation budget and the run properties need, on table3's kinematic level.
(c): one design evaluated at each level by ``evaluate_design`` with a budget in propagations,
so every round does the same planning work and the time measures speed only.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from experiments.sweep.config import config_from_dict
from experiments.sweep.job import evaluate_design, sweep_job
from feeders.design import PRESETS
from feeders.feeder import build_feeder
from planners.adapters import state_propagator, validity_checker
from planners.spaces import make_state_space, state_codec
from validity import make_level

CALLS = 2000
BUDGETS = {"geometric": 20000, "kinematic": 6000, "dynamic": 1500}


@functools.cache
def _states():
    scene = build_feeder(PRESETS["table3"], name="table3")
    level = make_level("kinematic", scene)
    space = make_state_space(scene, level.state_dim, level.velocity_limit)
    _, write = state_codec(level.state_dim)
    start, result = space.allocState(), space.allocState()
    write(start, level.state_of_pose(scene.start("heavy_leading")))
    control = [0.5, -0.5, 0.2]
    return level, start, result, control


@pytest.mark.parametrize("counted", [False, True], ids=["plain", "counted"])
def test_bench_callbacks(benchmark, counted: bool) -> None:
    """(a) plain, (b) counted: CALLS x (isValid + propagate 0.05 s) through the adapters."""
    level, start, result, control = _states()
    counts = [0, 0] if counted else None
    check, propagate = validity_checker(level, counts), state_propagator(level, counts)
    propagate(start, control, 0.05, result)  # compile before timing

    def calls() -> None:
        for _ in range(CALLS):
            propagate(start, control, 0.05, result)
            check(result)

    benchmark.extra_info["calls_per_round"] = CALLS
    benchmark(calls)


@pytest.mark.parametrize("level", list(BUDGETS))
def test_bench_evaluate_design(benchmark, level: str) -> None:
    """(c) table3 at one level, RRT, one run per entry, a budget in propagations."""
    config = config_from_dict(
        {
            "designs": {"count": 1},
            "feeder": {"inputs": {"max_force": 10.0, "max_torque": 2.0}},
            "ladder": [
                {"level": level, "planners": ["rrt"], "budget": {"propagations": BUDGETS[level]}}
            ],
        }
    )
    values = [float(v) for v in PRESETS["table3"].to_vector()]
    job = sweep_job(dataclasses.replace(config, seed=1, name="bench"), 0, values, 0)
    evaluate_design(job)  # compile before timing
    result = benchmark.pedantic(evaluate_design, args=(job,), rounds=5, iterations=1)
    benchmark.extra_info["status"] = result["status"]
    benchmark.extra_info["propagations"] = int(np.sum([r["propagations"] for r in result["runs"]]))
