"""What every benchmark shares: timing loops long enough to swamp the timer, statistics over
repeats (median, min, max, quartiles), time to a first plan, and where it was measured.

Measure, never assert: these return numbers for reports, they judge nothing.
"""

from __future__ import annotations

import importlib.metadata
import os
import platform
import statistics
import time
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np

from feeders.scene import Scene

MIN_REPEAT_TIME = 0.05  # s: each repeat loops over its workload for at least this long
REPO_ROOT = Path(__file__).resolve().parents[2]


def stats(values: list[float]) -> dict:
    """Median, min, max and quartiles of repeated measurements."""
    q1 = q3 = values[0]
    if len(values) > 1:
        q1, _, q3 = statistics.quantiles(values, n=4, method="inclusive")
    return {
        "median": statistics.median(values),
        "min": min(values),
        "max": max(values),
        "q1": q1,
        "q3": q3,
        "repeats": len(values),
    }


def per_item_us(run: Callable[[], object], items: int, repeats: int) -> dict:
    """Microseconds per item of ``run`` (which processes ``items`` items), over ``repeats``."""
    run()  # warm: compiled code loaded, caches filled
    loops = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(loops):
            run()
        if time.perf_counter() - t0 >= MIN_REPEAT_TIME:
            break
        loops *= 2
    per_item = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(loops):
            run()
        per_item.append((time.perf_counter() - t0) / (loops * items) * 1e6)
    return {**stats(per_item), "items": items, "loops": loops}


def bench_planning(
    scene: Scene,
    seeds: int,
    time_limit: float = 10.0,
    level: str = "geometric",
    planner: str = "rrt",
) -> dict:
    """(e) A planner on a level (default: RRT, geometric): time to the first solution (s; an
    unsolved run counts as the time limit), solved fraction and tree size, per start
    orientation."""
    from planners.plan import plan  # imported here: OMPL is only needed for this measurement

    out = {}
    for orientation in scene.starts:
        runs = [
            plan(scene, level, planner, orientation, time_limit=time_limit, seed=s)
            for s in range(1, seeds + 1)
        ]
        times = [r.time if r.solved else time_limit for r in runs]
        out[orientation] = {
            **stats(times),
            "solved_fraction": sum(r.solved for r in runs) / len(runs),
            "median_tree_size": statistics.median(r.tree_size for r in runs),
            "seeds": [1, seeds],
            "time_limit": time_limit,
        }
    return out


def cpu_model() -> str:
    """The processor's name (Linux: /proc/cpuinfo), else what ``platform`` says."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_info() -> dict:
    """Where the numbers were measured: cores, platform and library versions."""

    def version(dist: str) -> str:
        try:
            return importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            return "not installed"

    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return {
        "cpu": cpu_model(),
        "cores": os.cpu_count(),
        "usable_cores": usable,
        "platform": platform.platform(),
        "machine": platform.machine(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "numba": version("numba"),
        "ompl": version("ompl"),
        "python-fcl": version("python-fcl"),
        "shapely": version("shapely"),
    }


def interleaved_seconds(
    runs: Mapping[str, tuple[Callable[[], object], Callable[[], object]]], repeats: int
) -> dict[str, list[float]]:
    """Seconds of each run's timed call over ``repeats`` rounds, the runs interleaved.

    ``runs`` maps a key to ``(prepare, timed)``: ``prepare`` (untimed) resets the run, then
    ``timed`` is timed once. Each round visits every run once, starting one further along each
    round, so slow drifts of a shared machine fall on every run alike; one untimed warm-up
    round comes first (compiled code loaded, caches filled). Take medians of the lists.
    """
    if repeats < 1:
        raise ValueError(f"repeats = {repeats} must be >= 1")
    keys = list(runs)
    out: dict[str, list[float]] = {k: [] for k in keys}
    for round_ in range(repeats + 1):
        shift = round_ % len(keys) if keys else 0
        for key in keys[shift:] + keys[:shift]:
            prepare, timed = runs[key]
            prepare()
            t0 = time.perf_counter()
            timed()
            elapsed = time.perf_counter() - t0
            if round_:
                out[key].append(elapsed)
    return out
