"""What a long job shows while it works, on stderr (stdout stays for the results: ``--json``
is never mixed with it): bars whose total is fixed when they start, so that the percentage
and tqdm's time estimate (remaining = left / rate so far) mean something, and, for a phase
with nothing to count (writing a report), a line when it starts and its time when it ends.

Like the bars, the lines are written only on a terminal (``stream`` None: stderr, when it is
one): a script reading stderr, or a batch job's log, gets what it got before, errors and the
compile notice (:mod:`experiments.cli.kernels`). Tests hand in a ``StringIO`` to read what would
be drawn."""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any, TextIO


def bar(total: int, desc: str, unit: str, initial: int = 0, stream: TextIO | None = None) -> Any:
    """A tqdm bar over ``total`` items (``initial`` of them done before this process: a
    resumed job), with its elapsed time and time estimate. ``stream`` None draws on stderr
    when it is a terminal; a given stream is always drawn on."""
    from tqdm import tqdm

    return tqdm(
        total=total,
        initial=initial,
        desc=desc,
        unit=unit,
        file=sys.stderr if stream is None else stream,
        dynamic_ncols=stream is None,
        leave=True,
        disable=None if stream is None else False,
    )


@contextmanager
def phase(what: str, quiet: bool = False, stream: TextIO | None = None) -> Iterator[None]:
    """``partfeeder: WHAT ...`` when the phase starts, its wall time (s) when it ends, on
    stderr (or ``stream``); nothing when ``quiet``. A phase that raises ends its line
    without a time, so the error's own line starts on a line of its own."""
    out = None if quiet else _terminal(stream)
    if out is not None:
        print(f"partfeeder: {what} ...", end="", file=out, flush=True)
    t0 = time.perf_counter()
    try:
        yield
    except BaseException:
        if out is not None:
            print(file=out, flush=True)
        raise
    if out is not None:
        print(f" {time.perf_counter() - t0:.1f} s", file=out, flush=True)


def say(line: str, quiet: bool = False, stream: TextIO | None = None) -> None:
    """One line ``partfeeder: LINE`` on stderr (or ``stream``), unless ``quiet``."""
    out = _terminal(stream)
    if not quiet and out is not None:
        print(f"partfeeder: {line}", file=out, flush=True)


def _terminal(stream: TextIO | None) -> TextIO | None:
    """Where the lines go: ``stream`` when given, else stderr when it is a terminal."""
    if stream is not None:
        return stream
    isatty = getattr(sys.stderr, "isatty", None)
    return sys.stderr if isatty is not None and isatty() else None


class PhaseBars:
    """One bar per phase of a job whose later phases are sized by the earlier ones' results
    (the part calibration: the geometric verdicts go to the shapes the passive columns
    chose): each phase's bar starts when its jobs are queued, with their number as its fixed
    total, so its percentage and time estimate mean something (a single bar whose total grew
    as jobs were queued read 100% whenever it caught up). ``note(label, queued)`` is the
    job's progress callback: ``queued`` > 0 opens the phase ``label`` with that total (a
    phase queued again in two parts gets a bar for each), 0 counts one job done."""

    def __init__(self, desc: str, unit: str = "job", stream: TextIO | None = None) -> None:
        self.desc, self.unit, self.stream = desc, unit, stream
        self.current: Any = None

    def note(self, label: str, queued: int) -> None:
        if queued > 0:
            self.close()
            self.current = bar(queued, f"{self.desc}: {label}", self.unit, stream=self.stream)
        elif self.current is not None:
            self.current.update()

    def close(self) -> None:
        if self.current is not None:
            self.current.close()
            self.current = None

    def __enter__(self) -> PhaseBars:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
