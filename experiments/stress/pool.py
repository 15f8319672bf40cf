"""Run the cases of a seed in worker processes (the shared local pool,
:mod:`experiments.executors.local`): each worker generates its own cases from
``(seed, index)`` and builds its own scenes and levels, so only indices go out and records
come back. Results are in index order whatever the number of workers."""

from __future__ import annotations

import functools
import time
from collections.abc import Callable, Sequence
from typing import Any

from experiments.executors.local import map_jobs
from experiments.stress.case import LEVEL_NAMES
from experiments.stress.generate import composite_index, generate_case, ramp_foot_index
from experiments.stress.runner import record_of

Result = tuple[dict[str, Any], float]
CHUNK = 16  # cases per task: few round trips, a smooth progress bar


def run_one(seed: int, levels: tuple[str, ...], index: int, step: float | None = None) -> Result:
    """Generate and run case ``index`` of ``seed`` (at h = ``step`` if given): its record and
    wall time (s, both). A case that cannot be generated is recorded as an exception (a fault
    of the generator)."""
    start = time.perf_counter()
    try:
        case = generate_case(seed, index, levels, step)
    except Exception as exc:
        level = levels[index % len(levels)]
        record = {
            "seed": seed,
            "index": index,
            "level": level,
            "family": "?",
            "placement": "?",
            "h": 1.0 if step is None else step,
            "max_depth": 0.0,
            "depth_allowed": 0.0,
            "step_error": 0.0,
            "part_size": 0.0,
            "energy_gain": 0.0,
            "energy_allowed": 0.0,
            "crossed_step": None,
            "error": f"generate: {type(exc).__name__}: {exc}",
            "hard": ["exception"],
            "soft": [],
        }
        return record, time.perf_counter() - start
    return record_of(case), time.perf_counter() - start


def warm_up(levels: tuple[str, ...]) -> None:
    """Compile (or load) every level's kernels, so no case's time counts them."""
    for level in levels:
        record_of(generate_case(0, LEVEL_NAMES.index(level), LEVEL_NAMES))


def run_chunk(
    seed: int, levels: tuple[str, ...], step: float | None, indices: Sequence[int]
) -> list[Result]:
    """Generate and run the cases ``indices`` of ``seed`` (a worker's task)."""
    return [run_one(seed, levels, i, step) for i in indices]


def run_cases(
    seed: int,
    n_cases: int,
    levels: tuple[str, ...],
    workers: int,
    progress: Callable[[int], None] | None = None,
    n_composite: int = 0,
    n_ramp_foot: int = 0,
    step: float | None = None,
) -> list[Result]:
    """``(record, seconds)`` of cases 0 .. n_cases - 1 of ``seed``, of its composite-part
    cases 0 .. n_composite - 1 (:func:`experiments.stress.generate.composite_index`) and of its
    ramp-foot cases 0 .. n_ramp_foot - 1 (:func:`experiments.stress.generate.ramp_foot_index`),
    in index order, each at h = ``step`` if given; ``progress(k)`` is called as each batch of
    k cases finishes."""
    indices = list(range(n_cases)) + [composite_index(j) for j in range(n_composite)]
    indices += [ramp_foot_index(j) for j in range(n_ramp_foot)]
    chunks = [indices[i : i + CHUNK] for i in range(0, len(indices), CHUNK)]
    results = map_jobs(
        functools.partial(run_chunk, seed, levels, step),
        chunks,
        workers,
        on_result=None if progress is None else lambda k, _records: progress(len(chunks[k])),
        warm_up=functools.partial(warm_up, levels),
        ompl=False,
    )
    return [result for chunk in results for result in chunk]


def progress_bar(total: int) -> tuple[Callable[[int], None] | None, Callable[[], None]]:
    """``(update, close)`` of a bar over the cases on stderr: redrawn on a terminal, lines
    with done/total and the time left in a log (:mod:`experiments.progress`)."""
    from experiments.progress import bar

    cases = bar(total, "stress", "case")
    return cases.update, cases.close
