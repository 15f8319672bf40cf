"""Every compiled kernel a level uses, compiled once per machine: in one process, before any
worker process needs them.

The kernels are numba ``@njit(cache=True)`` functions: compiled for their argument types on
first call, then saved to numba's on-disk cache (``__pycache__`` beside the sources, or
``NUMBA_CACHE_DIR``, or a per-user cache directory when the installed package is not
writable), from which any later process loads them in well under a second. On a cold cache
(a fresh install, an edited source) every process that calls them compiles them itself: worker
processes started together each spend the same 15-30 s of CPU compiling the same kernels
(issue 22: ``partfeeder run`` of 8 designs took 33 s cold against 4 s warm). Calling
:func:`compile_kernels` in the parent before the workers start makes it one compile, and the
workers only load.

A level's kernels are reached by exercising its public interface (:class:`validity.level.Level`
and each level's own runs) for a few steps on the paper's table3 feeder: numba compiles a
kernel and every kernel it calls when it is first called with new argument types, so the
argument types matter, not the values or the branches taken.

Processes that start at once on a cold cache (two test runs, a test run and a command) would
each compile the same kernels: :func:`compile_kernels` holds a file lock beside numba's cache
(:func:`lock_path`), exclusive for the first comer, so the others wait for its compile and then
load what it saved. The kernel releases the lock when its process ends, however it ends.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

COMPILE_EVENT = "numba:compile"  # numba's event for a compile that missed the cache
EXERCISE_STEPS = 2  # steps of h per exercised run: enough to call every kernel's entry
LOCK_NAME = "partfeeder-kernels.lock"


@dataclass(frozen=True)
class KernelLoad:
    """What :func:`compile_kernels` did: ``compiled`` kernel signatures compiled (cache
    misses, saved to the cache), ``loaded`` loaded from the cache, in ``seconds`` of wall
    time (the imports included)."""

    levels: tuple[str, ...]
    compiled: int
    loaded: int
    seconds: float

    @property
    def cold(self) -> bool:
        """Whether anything was compiled (the cache lacked it)."""
        return self.compiled > 0


@contextmanager
def _on_first_compile(then: Callable[[], object] | None) -> Iterator[None]:
    """Within the block, ``then()`` is called when the first compile starts (numba's
    compile event fires on a cache miss only, never for a kernel loaded from the cache)."""
    if then is None:
        yield
        return
    announce: Callable[[], object] = then
    from numba.core import event

    class FirstCompile(event.Listener):
        started = False

        def on_start(self, _event: event.Event) -> None:
            if not self.started:
                self.started = True
                announce()

        def on_end(self, _event: event.Event) -> None:
            pass

    with event.install_listener(COMPILE_EVENT, FirstCompile()):
        yield


def kernel_dispatchers() -> list[Any]:
    """Every numba dispatcher (all ``cache=True``) of the ``validity`` modules imported so
    far, with their compile statistics (``stats.cache_hits``, ``stats.cache_misses``)."""

    from numba.core.registry import CPUDispatcher

    found = []
    for name, module in list(sys.modules.items()):
        if module is None or not (name == "validity" or name.startswith("validity.")):
            continue
        for obj in vars(module).values():
            if isinstance(obj, CPUDispatcher) and obj.__module__ == name:
                found.append(obj)
    return found


def kernel_counts() -> tuple[int, int]:
    """``(compiled, loaded)``: kernel signatures this process has compiled (cache misses)
    and loaded from the cache (hits) so far."""
    misses = hits = 0
    for dispatcher in kernel_dispatchers():
        stats = dispatcher.stats
        misses += sum(stats.cache_misses.values())
        hits += sum(stats.cache_hits.values())
    return misses, hits


NECESSARY = "necessary"  # the necessary-condition tests' kernels (validity.necessary)


def exercise(level_name: str) -> None:
    """Call every entry of the level ``level_name`` (its validity, clearance and runs) for a
    few steps on the table3 feeder, so each of its kernels is compiled or loaded; for
    ``necessary``, the necessary-condition tests on it."""
    from feeders.design import preset
    from feeders.feeder import build_feeder
    from validity import LEVELS

    scene = build_feeder(preset("table3"), name="table3")
    if level_name == NECESSARY:
        from validity.necessary import necessary_conditions

        necessary_conditions(scene)
        return
    level = LEVELS[level_name](scene)
    state = level.state_of_pose(next(iter(scene.starts.values())))
    low, high = level.control_bounds()
    control = tuple(float(v) for v in 0.5 * (low + high))
    duration = EXERCISE_STEPS * level.step
    level.is_valid(state)
    level.clearance(state)
    level.propagate(state, control, duration)
    path = getattr(level, "propagate_path", None)  # the moving part's recorded propagation
    if path is not None:
        path(state, control, duration)
    run = getattr(level, "run", None)  # the kinematic level's recorded run
    if run is not None:
        run(state, control, duration, True)
    simulate = getattr(level, "simulate", None)  # the dynamic level's drop (Eq. 10)
    if simulate is not None:
        simulate(state, duration=duration, y_stop=0.0, rest_speed=1e-3)


def lock_path() -> Path:
    """The lock file of :func:`compile_kernels`, in the directory numba saves this package's
    kernels to: ``NUMBA_CACHE_DIR`` when set, else ``__pycache__`` beside the sources when it
    is writable; else (numba then uses a per-user cache) a per-user file in the temporary
    directory. Processes on different caches never wait for each other."""
    from numba.core import config

    cache_dir = getattr(config, "CACHE_DIR", "")  # set from NUMBA_CACHE_DIR at numba's import
    if cache_dir:
        return Path(cache_dir) / LOCK_NAME
    in_tree = Path(__file__).resolve().parent / "__pycache__"
    try:
        in_tree.mkdir(exist_ok=True)
    except OSError:
        pass
    if os.access(in_tree, os.W_OK):
        return in_tree / LOCK_NAME
    return Path(tempfile.gettempdir()) / f"{LOCK_NAME}.{os.getuid()}"


@contextmanager
def one_compile_at_a_time(path: Path) -> Iterator[None]:
    """Within the block, no other process's block on ``path`` compiles at the same time: the
    first comer holds ``path`` locked exclusively (``flock``); a process that finds it held
    waits for its release and then shares the lock with any other waiter (they load what the
    first compiled, in parallel). Without ``fcntl`` (not POSIX), no lock."""
    try:
        import fcntl
    except ImportError:
        yield
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a") as handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            fcntl.flock(handle, fcntl.LOCK_SH)  # another compiles (or loads): wait for it
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def compile_kernels(
    levels: Iterable[str],
    on_first_compile: Callable[[], object] | None = None,
    on_level: Callable[[str], object] | None = None,
) -> KernelLoad:
    """Compile, or load from numba's cache, every kernel of ``levels`` (names of
    ``validity.LEVELS``, or ``necessary``) in this process, so processes started afterwards
    on this machine load them from the cache. ``on_first_compile()`` is called once, when
    the first kernel missing from the cache starts compiling (the moment to tell a user why
    they wait); ``on_level(name)`` after each level's kernels are ready (a progress bar's
    step). Another process compiling at the same time is waited for, then loaded from
    (:func:`one_compile_at_a_time`)."""
    chosen = tuple(dict.fromkeys(levels))
    from validity import LEVELS

    unknown = [name for name in chosen if name not in LEVELS and name != NECESSARY]
    if unknown:
        raise ValueError(f"unknown level {unknown[0]!r}; levels: {', '.join(LEVELS)}")
    start = time.perf_counter()
    misses0, hits0 = kernel_counts()
    with one_compile_at_a_time(lock_path()), _on_first_compile(on_first_compile):
        for name in chosen:
            exercise(name)
            if on_level is not None:
                on_level(name)
    misses, hits = kernel_counts()
    return KernelLoad(chosen, misses - misses0, hits - hits0, time.perf_counter() - start)
