"""Planning from several threads of one process: OMPL's generator is process-wide, so the
planning entry points take turns (issue 23: a Dask worker with two threads gave other trees
for the same seeds, and crashed). The reference is the same queries run one after another."""

from __future__ import annotations

import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from feeders.design import PRESETS
from feeders.feeder import build_feeder
from planners.benchmark import Budget, benchmark_problem
from planners.plan import plan

SEEDS = (1, 2, 3, 4)
PROPAGATIONS = 1500


@pytest.fixture(scope="module")
def table3():
    return build_feeder(PRESETS["table3"], name="table3")


def _plan(scene, seed: int):
    result = plan(scene, "geometric", "rrt", "heavy_leading", 60.0, seed, propagations=PROPAGATIONS)
    return result.tree_size, result.propagations, result.tree_vertices


def _benchmark(scene, seed: int):
    rows = benchmark_problem(
        scene,
        "geometric",
        "heavy_trailing",
        ["rrt", "kpiece"],
        2,
        Budget(time_s=60.0, propagations=PROPAGATIONS),
        seed,
        "threads",
    ).runs
    return [(r["planner"], r["seed"], r["tree_size"], r["propagations"]) for r in rows]


@pytest.mark.parametrize("query", [_plan, _benchmark], ids=["plan", "benchmark_problem"])
def test_four_threads_planning_at_once_give_the_serial_results(table3, query) -> None:
    serial = [query(table3, seed) for seed in SEEDS]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # threads take turns every few bytecodes, not every 5 ms
    try:
        with ThreadPoolExecutor(4) as pool:
            threaded = list(pool.map(lambda seed: query(table3, seed), SEEDS))
    finally:
        sys.setswitchinterval(interval)
    for want, got in zip(serial, threaded, strict=True):
        for a, b in zip(want, got, strict=True):
            np.testing.assert_array_equal(a, b)
