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


def sleep_then_square(x: int) -> int:
    """A long job (``x`` >= 100 sleeps a minute): what a stop request must not wait for."""
    import time

    if x >= 100:
        time.sleep(60)
    return x * x
