"""How long a job has left, for the progress lines and bars of :mod:`experiments.progress`.

Two rules, both plain arithmetic on counts and seconds (the clock is the caller's):

- :func:`rate_eta`, for items of about equal cost (a margin's axes, a stress run's cases):
  remaining = items left x seconds per item so far, the rule of tqdm and rich.
- :class:`LadderEta`, for items that climb stages of rising cost and may stop at any of them
  (the sweep's designs up the ladder of levels, Sec. 4): the cheap first stage ends first
  and stops most items, so a rate over items finished says "00:02" while the expensive
  stages have not started (issue 39: "00:02" for 87 s, then "03:22"). Each stage's mean
  cost c_r (worker-seconds per job) and the fraction p_r of its items that go on are
  measured as results come; an item waiting at stage r is expected to cost
  E_r = c_r + p_r E_{r+1} (E past the top = 0) more worker-seconds, and the work left is
  spent at the rate measured so far (worker-seconds done per second of wall time, so the
  number of workers needs no knowing).

A stage no result has come from yet has no measured cost: it is taken to cost what the
costliest stage below it measured (the ladder's stages cost more as they go up) and to stop
every item (nothing is counted past it), so the estimate is then a lower bound, marked
``at_least``, shown as "ETA >= 00:05", never a plain number known to be too small. It
becomes an expectation, unmarked, once every stage that may still get work has reported.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass


@dataclass(frozen=True)
class Eta:
    """Seconds of wall time left; ``at_least`` when it is a lower bound, not an estimate."""

    seconds: float
    at_least: bool = False

    def text(self) -> str:
        """``03:22``, ``>= 00:05`` for a lower bound, ``1:02:03`` past an hour."""
        return (">= " if self.at_least else "") + clock_text(self.seconds)


def clock_text(seconds: float) -> str:
    """``mm:ss``, or ``h:mm:ss`` from an hour on (tqdm's format)."""
    s = max(0, round(seconds))
    hours, rest = divmod(s, 3600)
    minutes, secs = divmod(rest, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes:02d}:{secs:02d}"


def rate_eta(elapsed: float, done: int, left: int) -> Eta | None:
    """Items of equal cost: ``left`` x ``elapsed`` / ``done`` (``done`` counted in this run:
    items done before it, a resumed job's, took none of ``elapsed``). None before the first
    item: nothing measured yet."""
    if left <= 0:
        return Eta(0.0)
    if done <= 0 or elapsed <= 0:
        return None
    return Eta(left * elapsed / done)


class LadderEta:
    """The time left of items climbing ``stages`` stages (see the module's rule). ``waiting``
    gives, at the start, the stage of each unfinished item's next job (a resumed sweep's
    designs wait at different rungs); :meth:`result` records each job as it ends, with its
    cost in worker-seconds (None when unknown: a job given up) and whether its item goes on
    to the next stage."""

    def __init__(self, stages: int, waiting: Sequence[int]) -> None:
        self.waiting = [0] * stages
        for stage in waiting:
            self.waiting[stage] += 1
        self.jobs = [0] * stages  # results per stage
        self.went_on = [0] * stages
        self.costed = [0] * stages  # results with a known cost
        self.cost = [0.0] * stages  # their worker-seconds
        self.spent = 0.0

    def result(self, stage: int, cost_s: float | None, goes_on: bool) -> None:
        self.waiting[stage] -= 1
        self.jobs[stage] += 1
        if goes_on:
            self.went_on[stage] += 1
            if stage + 1 < len(self.waiting):
                self.waiting[stage + 1] += 1
        if cost_s is not None:
            self.costed[stage] += 1
            self.cost[stage] += cost_s
            self.spent += cost_s

    def work_left(self) -> tuple[float, bool] | None:
        """Expected worker-seconds left and whether that is a lower bound; None while no
        stage has a measured cost."""
        known = [c / k if k else None for c, k in zip(self.cost, self.costed, strict=True)]
        if all(c is None for c in known):
            return None
        costs: list[float] = []
        for c in known:
            costs.append(c if c is not None else max(costs, default=0.0))
        expected = [0.0] * (len(costs) + 1)  # E_r, with E past the top = 0
        for r in reversed(range(len(costs))):
            on = self.went_on[r] / self.jobs[r] if self.jobs[r] and known[r] is not None else 0.0
            expected[r] = costs[r] + on * expected[r + 1]
        left = sum(n * e for n, e in zip(self.waiting, expected, strict=False))
        return left, bool(self.untimed())

    def untimed(self) -> list[int]:
        """The stages with no measured cost yet at or above the lowest one an item waits at:
        those whose cost the estimate guesses (it is a lower bound while there are any)."""
        lowest = next((r for r, n in enumerate(self.waiting) if n > 0), len(self.waiting))
        return [r for r in range(lowest, len(self.waiting)) if not self.costed[r]]

    def eta(self, elapsed: float) -> Eta | None:
        """Wall time left after ``elapsed`` seconds of this run: the work left at the rate of
        worker-seconds done per second so far. None before any cost is measured."""
        if not any(self.waiting):
            return Eta(0.0)
        work = self.work_left()
        if work is None or self.spent <= 0 or elapsed <= 0:
            return None
        left, at_least = work
        return Eta(left * elapsed / self.spent, at_least)
