"""Start-up of every local worker process the jobs start (the sweep and the optimiser's pool,
stress, feasibility, calibration, the agreement suite): a worker dies with its parent and
leaves interrupts to it.

- Ctrl-C reaches the whole process group: the workers ignore SIGINT, so only the parent
  reacts (it stores what is done, releases its lock and says so in one line) and no worker
  prints a traceback.
- A worker whose parent has died (``kill -9``, a crash, a batch scheduler's SIGKILL) ends
  within ``PARENT_POLL_S``: a daemon thread watches the parent's pid (the worker is
  re-parented when its parent dies), portable where Linux's parent-death signal is not, and
  not tied to the thread that started the worker.

Dask's workers are not ours to manage (``distributed`` ends them); only their OMPL log is
silenced (:func:`quiet_ompl`).
"""

from __future__ import annotations

import os
import signal
import threading
import time

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


def start_worker(ompl: bool = True) -> None:
    """Run first in a worker process: ignore SIGINT, end with the parent, and (``ompl``)
    silence OMPL's log."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(
        target=_watch_parent, args=(os.getppid(),), daemon=True, name="parent-watch"
    ).start()
    if ompl:
        quiet_ompl()
