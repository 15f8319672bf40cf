"""pytest-benchmark timings of the geometric level on table3: measure, never assert.

Run explicitly (the default test run collects only ``tests/``)::

    python -m pytest benchmarks -q

The workload is :func:`experiments.bench.geometric.table3_workload` (seed 1): the same poses and
propagations ``partfeeder bench`` measures. Each benchmark times one pass over its batch;
``extra_info`` records the batch size so per-check / per-step times can be read off.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from experiments.bench.geometric import PROPAGATION_DURATION, Workload, count_valid, table3_workload


@functools.cache
def _workload() -> Workload:
    return table3_workload(seed=1)


@pytest.fixture
def work() -> Workload:
    return _workload()


def test_bench_is_valid_python(benchmark, work: Workload) -> None:
    """(a) GeometricLevel.is_valid called from Python, once per pose of the batch."""
    poses, is_valid = work.pose_tuples, work.level.is_valid
    benchmark.extra_info["checks_per_round"] = len(poses)
    benchmark(lambda: [is_valid(p) for p in poses])


def test_bench_is_valid_compiled(benchmark, work: Workload) -> None:
    """(b) pose_is_valid over the batch inside one compiled numba loop (compiled before timing)."""
    a = work.level.arrays
    poses = np.ascontiguousarray(work.poses)
    args = (poses, *a.pose_scene)
    count_valid(*args)
    benchmark.extra_info["checks_per_round"] = len(poses)
    benchmark(count_valid, *args)


@pytest.mark.parametrize("cases", ["free", "hit"])
def test_bench_propagate(benchmark, work: Workload, cases: str) -> None:
    """(d) GeometricLevel.propagate over the free-motion or wall-hitting cases."""
    chosen = work.free_cases if cases == "free" else work.hit_cases
    propagate = work.level.propagate
    benchmark.extra_info["steps_per_round"] = sum(steps for *_, steps in chosen)
    benchmark(lambda: [propagate(q, u, PROPAGATION_DURATION) for q, u, _ in chosen])
