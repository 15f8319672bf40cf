"""Run the cases of a seed in worker processes (spawn): each worker generates its own cases
from ``(seed, index)`` and builds its own scenes and levels, so only indices go out and
records come back. Results are in index order whatever the number of workers."""

from __future__ import annotations

import multiprocessing
import sys
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any

from experiments.stress.case import LEVEL_NAMES
from experiments.stress.generate import generate_case
from experiments.stress.runner import record_of
from experiments.worker_process import start_plain_worker

Result = tuple[dict[str, Any], float]
CHUNK = 16  # cases per task: few round trips, a smooth progress bar


def run_one(seed: int, levels: tuple[str, ...], index: int) -> Result:
    """Generate and run case ``index`` of ``seed``: its record and wall time (s, both). A case
    that cannot be generated is recorded as an exception (a fault of the generator)."""
    start = time.perf_counter()
    try:
        case = generate_case(seed, index, levels)
    except Exception as exc:
        level = levels[index % len(levels)]
        record = {
            "seed": seed,
            "index": index,
            "level": level,
            "family": "?",
            "placement": "?",
            "h": 1.0,
            "max_depth": 0.0,
            "depth_allowed": 0.0,
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
    """Start a worker (:func:`experiments.worker_process.start_worker`) and compile (or load)
    every level's kernels in it, so no case's time counts them."""
    start_plain_worker()
    for level in levels:
        record_of(generate_case(0, LEVEL_NAMES.index(level), LEVEL_NAMES))


def run_chunk(seed: int, levels: tuple[str, ...], indices: Sequence[int]) -> list[Result]:
    """Generate and run the cases ``indices`` of ``seed`` (a worker's task)."""
    return [run_one(seed, levels, i) for i in indices]


def run_cases(
    seed: int,
    n_cases: int,
    levels: tuple[str, ...],
    workers: int,
    progress: Callable[[int], None] | None = None,
) -> list[Result]:
    """``(record, seconds)`` of cases 0 .. n_cases - 1 of ``seed``, in index order;
    ``progress(k)`` is called as each batch of k cases finishes."""
    chunks = [list(range(i, min(i + CHUNK, n_cases))) for i in range(0, n_cases, CHUNK)]
    results: dict[int, list[Result]] = {}
    if workers <= 1:
        warm_up(levels)
        for k, chunk in enumerate(chunks):
            results[k] = run_chunk(seed, levels, chunk)
            if progress:
                progress(len(chunk))
    else:
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(
            workers, mp_context=context, initializer=warm_up, initargs=(levels,)
        ) as pool:
            futures = {
                pool.submit(run_chunk, seed, levels, chunk): k for k, chunk in enumerate(chunks)
            }
            for future in as_completed(futures):
                results[futures[future]] = future.result()
                if progress:
                    progress(len(chunks[futures[future]]))
    return [result for k in range(len(chunks)) for result in results[k]]


def progress_bar(total: int) -> tuple[Callable[[int], None] | None, Callable[[], None]]:
    """``(update, close)`` of a tqdm bar on stderr when it is a terminal, else no bar."""
    if not sys.stderr.isatty():
        return None, lambda: None
    from tqdm import tqdm

    bar = tqdm(total=total, desc="stress", unit="case", file=sys.stderr)
    return bar.update, bar.close
