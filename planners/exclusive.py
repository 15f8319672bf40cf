"""One seeded OMPL planning job at a time in a process.

OMPL's random generator is process-wide (``ompl.util.RNG.setSeed`` restarts the seed
sequence every object's generator draws from), and its Python callbacks are not made to run
in two planners at once. Two threads planning in one process (a Dask worker with
``--nthreads 2``, a researcher's thread pool) interleave their draws, so the same seed gives
another tree, or crash the process (measured: SIGSEGV in a Dask worker with two threads).
:func:`one_at_a_time` makes a planning entry point hold this process's lock from seeding to
its last OMPL object, so the same seed gives the same result on any worker layout; processes
still plan in parallel. Python's callbacks hold the GIL for most of a run, so serialising
threads costs little.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable
from typing import ParamSpec, TypeVar

P = ParamSpec("P")
R = TypeVar("R")

# The one lock of the process, as OMPL's generator is the one of the process. Re-entrant: a
# planning entry point may call another.
_OMPL = threading.RLock()


def one_at_a_time(function: Callable[P, R]) -> Callable[P, R]:
    """``function`` run while holding the process's OMPL lock; its OMPL objects, local to
    it, are released before the lock is."""

    @functools.wraps(function)
    def exclusive(*args: P.args, **kwargs: P.kwargs) -> R:
        with _OMPL:
            return function(*args, **kwargs)

    return exclusive
