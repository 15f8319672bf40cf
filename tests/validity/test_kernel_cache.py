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
import select
import subprocess
import sys
import time
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


# The same, its first compile paused (once it holds the lock) until a line on stdin: a second
# process is started meanwhile, a count of events, not a time, making the two concurrent.
COMPILE_PAUSED = """
import json, sys
from validity.kernel_cache import compile_kernels
def paused():
    print("compiling", flush=True)
    sys.stdin.readline()
load = compile_kernels(sys.argv[1].split(","), on_first_compile=paused)
print(json.dumps({"compiled": load.compiled, "loaded": load.loaded}))
"""
HANG_GUARD_S = 600.0  # only a failure waits this long (a loaded machine compiles in ~100 s)
# A process in the compile lock's block until a line on stdin, saying when it is inside.
HOLD_THE_LOCK = """
import sys
from pathlib import Path
from validity.kernel_cache import one_compile_at_a_time
with one_compile_at_a_time(Path(sys.argv[1])):
    print("inside", flush=True)
    sys.stdin.readline()
"""


def _waits_for_a_lock(pid: int) -> bool:
    """``pid`` is blocked waiting for a file lock (the kernel's table of locks: a waiter's
    line has ``->``)."""
    with open("/proc/locks") as f:
        return any("->" in line and line.split()[5] == str(pid) for line in f)


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


def _wait_until_waiting(process: subprocess.Popen) -> None:
    """Until ``process`` waits for the lock; it failing to wait fails at once: it ended, or
    it said it is inside (its stdout is readable)."""
    deadline = time.monotonic() + HANG_GUARD_S
    while not _waits_for_a_lock(process.pid):
        assert process.poll() is None, "it ended without waiting"
        assert not select.select([process.stdout], [], [], 0)[0], "it got in without waiting"
        assert time.monotonic() < deadline, "it never waited for the lock"
        time.sleep(0.02)


@pytest.mark.skipif(not os.path.exists("/proc/locks"), reason="reads the kernel's lock table")
def test_the_compile_lock_makes_later_comers_wait_for_the_first_then_lets_them_in_together(
    tmp_path,
):
    """The lock's rule alone, without a compile: while the first process is inside, the
    others wait (the kernel's lock table lists them as waiters); once it leaves, they are
    inside at the same time (what they do then is load, which need not wait in turn)."""
    lock = tmp_path / "cache" / "kernels.lock"
    command = [sys.executable, "-c", HOLD_THE_LOCK, str(lock)]

    def start() -> subprocess.Popen:
        return subprocess.Popen(
            command, cwd=ROOT, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
        )

    processes = [start()]
    try:
        assert processes[0].stdout.readline().strip() == "inside"
        processes += [start(), start()]
        for later in processes[1:]:
            _wait_until_waiting(later)
        processes[0].stdin.write("\n")
        processes[0].stdin.flush()
        assert processes[0].wait(timeout=HANG_GUARD_S) == 0
        for later in processes[1:]:  # both inside before either is let out
            assert select.select([later.stdout], [], [], HANG_GUARD_S)[0], "it never got in"
            assert later.stdout.readline().strip() == "inside"
        for later in processes[1:]:
            later.stdin.write("\n")
            later.stdin.flush()
            assert later.wait(timeout=HANG_GUARD_S) == 0
    finally:
        for process in processes:
            if process.poll() is None:
                process.kill()
                process.wait()


@pytest.mark.skipif(not os.path.exists("/proc/locks"), reason="reads the kernel's lock table")
@pytest.mark.slow  # a cold compile (~20 s of CPU); the lock's rule alone is tested above
def test_a_process_that_starts_while_another_compiles_waits_and_only_loads(cold_cache):
    """Two processes on one cold cache at once (two test runs, a run and a command): the
    first compiles; the second, started while the first's compile is under way, waits for it
    and loads every kernel, compiling none (issue 39: without the lock each compiled them
    all). The necessary conditions' kernels: the fewest to compile."""
    command = [sys.executable, "-c", COMPILE_PAUSED, "necessary"]
    first = subprocess.Popen(
        command, cwd=ROOT, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    second = None
    try:
        assert first.stdin is not None and first.stdout is not None
        assert first.stdout.readline().strip() == "compiling"  # it holds the lock
        second = subprocess.Popen(
            command, cwd=ROOT, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, text=True
        )  # were it to compile (no lock), its pause would end at once
        deadline = time.monotonic() + HANG_GUARD_S
        while second.poll() is None and not _waits_for_a_lock(second.pid):
            assert time.monotonic() < deadline, "the second process neither waited nor ended"
            time.sleep(0.05)
        first.stdin.write("go on\n")
        first.stdin.flush()
        out_first, _ = first.communicate(timeout=HANG_GUARD_S)
        out_second, _ = second.communicate(timeout=HANG_GUARD_S)
    finally:
        for process in (first, second):
            if process is not None and process.poll() is None:
                process.kill()
                process.wait()
    assert first.returncode == 0 and second.returncode == 0
    compiled = json.loads(out_first.strip().splitlines()[-1])
    loaded = json.loads(out_second.strip().splitlines()[-1])
    assert compiled["compiled"] > 0 and compiled["loaded"] == 0
    assert "compiling" not in out_first  # one notice, however many kernels compile
    assert list(cold_cache.rglob("*.nbi"))  # numba's index files, in NUMBA_CACHE_DIR
    assert "compiling" not in out_second  # its compile never started
    assert loaded["compiled"] == 0 and loaded["loaded"] > 0


@pytest.mark.slow  # the concurrent test above starts the second process sooner: the same rule
def test_a_cold_cache_is_compiled_once_then_only_loaded(cold_cache):
    first = _compile_in_a_process("geometric", cold_cache)
    assert first["compiled"] > 0 and first["loaded"] == 0
    assert first["announced"] == 1  # one notice, however many kernels compile
    assert list(cold_cache.rglob("*.nbi"))  # numba's index files, in NUMBA_CACHE_DIR
    again = _compile_in_a_process("geometric", cold_cache)
    assert again == {"compiled": 0, "loaded": again["loaded"], "announced": 0}
    assert again["loaded"] > 0


@pytest.mark.slow  # a cold compile: ~40 s
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
