"""Start-up of every local worker process the jobs start (the sweep and the optimiser's pool,
stress, feasibility, calibration, the agreement suite): a worker dies with its parent and
leaves interrupts to it.

- Ctrl-C reaches the whole process group: the workers ignore SIGINT, so only the parent
  reacts (it stores what is done, releases its lock and says so in one line) and no worker
  prints a traceback. A worker is born with SIGINT blocked (:func:`worker_context`), so a
  Ctrl-C while it still imports its modules, before :func:`start_worker` can run, waits
  pending and is then discarded.
- A worker whose parent has died (``kill -9``, a crash, a batch scheduler's SIGKILL) ends
  within ``PARENT_POLL_S``: a daemon thread watches the parent's pid (the worker is
  re-parented when its parent dies), portable where Linux's parent-death signal is not, and
  not tied to the thread that started the worker. The parent's pid is the one it had when
  it started the worker, so a parent killed while the worker still imported is noticed too.

Dask's workers are not ours to manage (``distributed`` ends them); only their OMPL log is
silenced (:func:`quiet_ompl`).
"""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from multiprocessing.context import SpawnContext, SpawnProcess

PARENT_POLL_S = 0.5  # how often a worker looks for its parent (s)


def quiet_ompl() -> None:
    """OMPL's console log off (it would interleave with the progress bars)."""
    from ompl import util as ou

    ou.setLogLevel(ou.LogLevel.LOG_NONE)


def _watch_parent(parent: int) -> None:
    while True:
        time.sleep(PARENT_POLL_S)
        if os.getppid() != parent:
            os._exit(1)  # no cleanup to run: the parent that wanted the result is gone


@contextmanager
def sigint_blocked() -> Iterator[None]:
    """SIGINT held pending in this thread meanwhile (a process started here inherits the
    mask across ``exec``); a Ctrl-C that came is handled on leaving."""
    if not hasattr(signal, "pthread_sigmask"):  # not POSIX
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


class _WorkerProcess(SpawnProcess):
    def start(self) -> None:
        with sigint_blocked():
            super().start()


class _WorkerContext(SpawnContext):
    Process = _WorkerProcess


def worker_context() -> SpawnContext:
    """The ``spawn`` start method, its processes born with SIGINT blocked (for
    :func:`start_worker` to ignore): ``spawn``, since forking a parent that runs threads (a
    progress bar's monitor, numba's pool) can deadlock the child."""
    return _WorkerContext()


def start_worker(parent: int, ompl: bool = True) -> None:
    """Run first in a worker process started by ``parent`` (a pid) from
    :func:`worker_context`: ignore SIGINT, end with the parent, and (``ompl``) silence OMPL's
    log."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})  # a pending one is gone
    if os.getppid() != parent:
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True, name="parent-watch").start()
    if ompl:
        quiet_ompl()
