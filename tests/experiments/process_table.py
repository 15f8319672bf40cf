"""The kernel's process table, as the signal tests read it: who is alive, whose child it is,
and a start-up that makes a command (or this process, for a test) interruptible as from a
terminal."""

from __future__ import annotations

import os
import signal
import time
from collections.abc import Iterator
from contextlib import contextmanager


def processes() -> dict[int, int]:
    """Every live (not zombie) process and its parent, from the kernel's process table."""
    table = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    state, parent = f.read().rsplit(")", 1)[1].split()[:2]
            except (FileNotFoundError, ProcessLookupError):
                continue
            if state != "Z":
                table[int(entry)] = int(parent)
    return table


def children_of(pid: int) -> set[int]:
    return {p for p, parent in processes().items() if parent == pid}


def all_gone(pids: set[int], within_s: float = 300.0) -> bool:
    """Every one of ``pids`` has ended, looked at until ``within_s`` (the workers look for
    their parent every 0.5 s; only a failure waits the whole bound, which no loaded machine
    reaches: issue 22)."""
    deadline = time.monotonic() + within_s
    while time.monotonic() < deadline:
        if not pids & set(processes()):
            return True
        time.sleep(0.1)
    return False


def interruptible() -> None:
    """As from a terminal: a test runner started in the background passes SIGINT on ignored,
    and Python then never turns Ctrl-C into KeyboardInterrupt (a ``preexec_fn``)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@contextmanager
def sigint_as_from_a_terminal() -> Iterator[None]:
    """Within the block, Ctrl-C raises KeyboardInterrupt in this process, as in a test run
    started from a terminal; a test runner started in the background (``nohup ... &``)
    inherits SIGINT ignored, and a test of what Ctrl-C does in this process then fails
    (issue 39). The runner's own disposition is restored afterwards."""
    previous = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
