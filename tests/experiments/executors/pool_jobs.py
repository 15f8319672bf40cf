"""Jobs for the pool tests, importable by spawned workers (a test module is not)."""

from __future__ import annotations

import os
import signal


def square(x: int) -> int:
    return x * x


def fail_on_three(x: int) -> int:
    if x == 3:
        raise ValueError("three is refused")
    return x


def die_on_three(x: int) -> int:
    if x == 3:
        os.kill(os.getpid(), signal.SIGKILL)
    return x


def sigint_disposition(_x: int) -> bool:
    """True if this process ignores SIGINT (a worker must: Ctrl-C is the parent's)."""
    return signal.getsignal(signal.SIGINT) == signal.SIG_IGN


def sleep_then_square(x: int, finished_in: str | None = None) -> int:
    """A long job (``x`` >= 100 sleeps a minute, then leaves a file named ``x`` in the folder
    ``finished_in``): what a stop request must not wait for."""
    import time
    from pathlib import Path

    if x >= 100:
        time.sleep(60)
        if finished_in is not None:
            (Path(finished_in) / str(x)).touch()
    return x * x
