"""What a long job shows while it works, on stderr (stdout stays for the results: ``--json``
is never mixed with it), in one of two forms chosen by where stderr goes:

- a terminal: tqdm bars redrawn in place, whose total is fixed when they start, so that the
  percentage and the time estimate mean something; and, for a phase with nothing to count
  (writing a report), a line when it starts that gets its time when it ends;
- anything else (``partfeeder run 2>log``, a batch job's log, a pipe): plain lines, never a
  carriage return: a bar's start, a line each time a tenth of its items is done (or
  :data:`LogBar.EVERY` items, or :data:`LogBar.INTERVAL_S` seconds with work going on, since
  the last one, whichever comes first), each with done/total, the elapsed time and the
  estimate, and its end with its wall time; a phase's start and end with its wall time
  (issue 39: piped to a file, a sweep said nothing for 18 minutes).

The time estimate is tqdm's rule (items left x seconds per item so far) unless the caller
knows better and hands in ``estimate`` (:mod:`experiments.eta`: the sweep's designs climb
stages of rising cost, so a rate over the designs finished first is far too low). A caller's
``--quiet`` silences both forms: it makes no bar and calls :func:`phase` and :func:`say` with
``quiet``. A given ``stream`` is written in the form its ``isatty()`` asks for (tests hand in
a ``StringIO`` to read the lines a log would get)."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, TextIO

from experiments.eta import Eta, clock_text, rate_eta

Estimate = Callable[[float], Eta | None]  # seconds elapsed in this run -> time left


def bar(
    total: int,
    desc: str,
    unit: str,
    initial: int = 0,
    stream: TextIO | None = None,
    estimate: Estimate | None = None,
    clock: Callable[[], float] = time.monotonic,
) -> Any:
    """A bar over ``total`` items (``initial`` of them done before this process: a resumed
    job) on ``stream`` (default stderr): a tqdm bar on a terminal, a :class:`LogBar`
    elsewhere; both take ``update(n)``, ``set_postfix(_str)``, ``set_description``,
    ``refresh`` and ``close`` and are context managers. ``estimate`` replaces the rate rule
    of the time left; ``clock`` (s) is the log's (tests step it by hand)."""
    out = _target(stream)
    if not is_terminal(out):
        return LogBar(total, desc, initial, out, estimate, clock)
    from tqdm import tqdm

    options: dict[str, Any] = dict(
        total=total,
        initial=initial,
        desc=desc,
        unit=unit,
        file=out,
        dynamic_ncols=stream is None,
        leave=True,
    )
    if estimate is None:
        return tqdm(**options)
    rule: Estimate = estimate  # narrowed, for the class below

    class EstimatedBar(tqdm):  # tqdm reads its fields from format_dict
        @property
        def format_dict(self) -> dict[str, Any]:
            fields = super().format_dict
            eta = rule(fields["elapsed"])
            fields["eta"] = "?" if eta is None else eta.text()
            return fields

    fmt = "{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}, ETA {eta}{postfix}]"
    return EstimatedBar(bar_format=fmt, **options)


class LogBar:
    """A bar written as lines, for a stream that is not a terminal (see the module)."""

    SHARES = 10  # a line each time another tenth of the items is done
    EVERY = 50  # and at least every 50 items
    INTERVAL_S = 30.0  # and on an item done or a refresh, if 30 s passed since the last

    def __init__(
        self,
        total: int,
        desc: str,
        initial: int,
        out: TextIO,
        estimate: Estimate | None,
        clock: Callable[[], float],
    ) -> None:
        self.total, self.desc, self.initial, self.n = total, desc, initial, initial
        self.out, self.estimate, self.clock = out, estimate, clock
        self.postfix = ""
        self.closed = False
        self.t0 = self.last_t = clock()
        self.last_n = initial
        before = f", {initial} done before" if initial else ""
        self._line(f"{desc}: started, {total}{before}")

    def update(self, n: int = 1) -> None:
        before, self.n = self.n, self.n + n
        if self.n >= self.total:
            return  # the end line says it
        now = self.clock()
        share = self.SHARES * self.n // max(self.total, 1) > self.SHARES * before // max(
            self.total, 1
        )
        if share or self.n - self.last_n >= self.EVERY or now - self.last_t >= self.INTERVAL_S:
            self._progress(now)

    def _progress(self, now: float) -> None:
        self.last_n, self.last_t = self.n, now
        self._line(f"{self.desc}: {self.counts()}, {self.times(now)}{self.tail()}")

    def counts(self) -> str:
        """``30/64 (47%)``."""
        percent = 100 * self.n // self.total if self.total else 100
        return f"{self.n}/{self.total} ({percent}%)"

    def times(self, now: float) -> str:
        """``elapsed 00:12, ETA 00:14``: the estimate, or the rate rule over this run."""
        elapsed = now - self.t0
        if self.estimate is not None:
            eta = self.estimate(elapsed)
        else:
            eta = rate_eta(elapsed, self.n - self.initial, self.total - self.n)
        return f"elapsed {clock_text(elapsed)}, ETA {'?' if eta is None else eta.text()}"

    def tail(self) -> str:
        return f" | {self.postfix}" if self.postfix else ""

    def set_postfix_str(self, s: str = "", refresh: bool = True) -> None:
        self.postfix = s

    def set_postfix(self, refresh: bool = True, **fields: object) -> None:
        """tqdm's ``key=value, ...`` beside the counts."""
        self.postfix = ", ".join(f"{key}={value}" for key, value in fields.items())

    def set_description(self, desc: str, refresh: bool = True) -> None:
        self.desc = desc

    def refresh(self) -> None:
        """A line only if :data:`INTERVAL_S` has passed since the last one: the counts beside
        moved (a sweep's evaluations while no design finishes) and the log was quiet."""
        now = self.clock()
        if not self.closed and now - self.last_t >= self.INTERVAL_S:
            self._progress(now)

    def close(self) -> None:
        if self.closed:
            return
        self.closed = True
        took = clock_text(self.clock() - self.t0)
        if self.n >= self.total:
            self._line(f"{self.desc}: {self.counts()} done in {took}{self.tail()}")
        else:
            self._line(f"{self.desc}: stopped at {self.counts()} after {took}{self.tail()}")

    def _line(self, text: str) -> None:
        print(f"partfeeder: {text}", file=self.out, flush=True)

    def __enter__(self) -> LogBar:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


@contextmanager
def phase(what: str, quiet: bool = False, stream: TextIO | None = None) -> Iterator[None]:
    """``partfeeder: WHAT ...`` when the phase starts and its wall time (s) when it ends, on
    stderr (or ``stream``); nothing when ``quiet``. On a terminal the time ends the same line
    (a phase that raises ends it without a time, so the error's own line starts on a line
    of its own); in a log it is a line of its own, ``partfeeder: WHAT: done in 1.2 s``."""
    out = _target(stream)
    terminal = is_terminal(out)
    if not quiet:
        print(f"partfeeder: {what} ...", end="" if terminal else "\n", file=out, flush=True)
    t0 = time.perf_counter()
    try:
        yield
    except BaseException:
        if not quiet and terminal:
            print(file=out, flush=True)
        raise
    took = time.perf_counter() - t0
    if not quiet:
        print(
            f" {took:.1f} s" if terminal else f"partfeeder: {what}: done in {took:.1f} s",
            file=out,
            flush=True,
        )


def say(line: str, quiet: bool = False, stream: TextIO | None = None) -> None:
    """One line ``partfeeder: LINE`` on stderr (or ``stream``), unless ``quiet``."""
    if not quiet:
        print(f"partfeeder: {line}", file=_target(stream), flush=True)


def _target(stream: TextIO | None) -> TextIO:
    """Where the lines go: ``stream`` when given, else stderr (looked up when written: a
    test's capture replaces it)."""
    return sys.stderr if stream is None else stream


def is_terminal(stream: TextIO) -> bool:
    """Whether ``stream`` is a terminal (a bar is redrawn there; elsewhere lines are written)."""
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty is not None and isatty())
    except ValueError:  # a closed file
        return False


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
