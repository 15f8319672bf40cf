"""The kernels are compiled once per machine: :func:`validity.kernel_cache.compile_kernels` in
one process fills numba's on-disk cache, and worker processes started afterwards load every
kernel their real work uses from it and compile none (issue 22: on a cold cache each worker
of ``partfeeder run`` compiled them all itself, 58 s of CPU with 2 workers for 33 s with 1).

Each test gets a cold cache of its own (``NUMBA_CACHE_DIR`` in a temporary directory, which
numba prefers to ``__pycache__``); what is checked is counted (compiled and loaded kernel
signatures, numba's own statistics), not timed.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import kernel_jobs
import pytest

from experiments.executors.local import LocalPool
from validity.kernel_cache import compile_kernels

ROOT = Path(__file__).resolve().parents[2]

COMPILE = """
import json, sys
from validity.kernel_cache import compile_kernels
announced = []
load = compile_kernels(sys.argv[1].split(","), on_first_compile=lambda: announced.append(1))
print(json.dumps({"compiled": load.compiled, "loaded": load.loaded, "announced": len(announced)}))
"""


def _compile_in_a_process(levels: str, cache: Path) -> dict:
    """:func:`compile_kernels` of ``levels`` in a fresh process on the cache ``cache``."""
    done = subprocess.run(
        [sys.executable, "-c", COMPILE, levels],
        cwd=ROOT,
        env={**os.environ, "NUMBA_CACHE_DIR": str(cache)},
        capture_output=True,
        text=True,
        timeout=900,
        check=True,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.fixture
def cold_cache(tmp_path, monkeypatch) -> Path:
    """An empty numba cache for this test's processes (workers inherit the environment)."""
    cache = tmp_path / "numba-cache"
    cache.mkdir()
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache))
    return cache


def test_a_cold_cache_is_compiled_once_then_only_loaded(cold_cache):
    first = _compile_in_a_process("geometric", cold_cache)
    assert first["compiled"] > 0 and first["loaded"] == 0
    assert first["announced"] == 1  # one notice, however many kernels compile
    assert list(cold_cache.rglob("*.nbi"))  # numba's index files, in NUMBA_CACHE_DIR
    again = _compile_in_a_process("geometric", cold_cache)
    assert again == {"compiled": 0, "loaded": again["loaded"], "announced": 0}
    assert again["loaded"] > 0


def test_planning_workers_load_what_the_parent_compiled(cold_cache):
    """What ``partfeeder plan`` and a sweep's planning workers run (OMPL calling the level's
    checker and propagator) compiles nothing after the parent's warm-up."""
    _compile_in_a_process("geometric", cold_cache)
    with LocalPool(workers=2) as pool:
        counts = pool.map(kernel_jobs.plan_and_count, ["geometric", "geometric"])
    for compiled, loaded in counts:
        assert compiled == 0 and loaded > 0


@pytest.mark.slow
def test_every_rung_of_a_sweep_loads_what_the_parent_compiled(cold_cache):
    """Every rung's job (the passive verdict's drops, planning at each level) compiles
    nothing in a worker once the parent compiled the kernels of every level: what
    ``partfeeder run`` does before its workers start (a full cold compile: about 30 s of CPU)."""
    _compile_in_a_process("geometric,kinematic,dynamic", cold_cache)
    rungs = list(range(len(kernel_jobs.EVERY_RUNG["ladder"])))
    with LocalPool(workers=2) as pool:
        counts = pool.map(kernel_jobs.sweep_rung_and_count, rungs)
    for rung, (compiled, loaded) in zip(rungs, counts, strict=True):
        assert compiled == 0 and loaded > 0, kernel_jobs.EVERY_RUNG["ladder"][rung]


def test_an_unknown_level_is_refused():
    with pytest.raises(ValueError, match="unknown level 'nosuch'"):
        compile_kernels(["nosuch"])
