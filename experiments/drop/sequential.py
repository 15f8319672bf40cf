"""Wald's sequential probability ratio test (SPRT) of one entry's success probability: the
verdict's ``sprt`` rule (issue 21: most designs fail, and a test that stops as soon as the
evidence allows decides them in a few trials, not ten).

An entry is tested between two simple hypotheses about its drops' success probability p:
``works_p`` (a feeder worth building) and ``fails_p`` (one that is not). After n drops with k
successes the log-likelihood ratio is

    LLR(k, n) = k ln(works_p / fails_p) + (n - k) ln((1 - works_p) / (1 - fails_p)),

and the entry *works* the first time LLR >= ln((1 - b) / a), *fails* the first time
LLR <= ln(b / (1 - a)), with a = ``false_works`` (the probability of calling a ``fails_p``
entry working) and b = ``false_fails`` (of calling a ``works_p`` entry failing): Wald's
bounds, which keep each error at most about its rate whenever one looks. The verdict's test
has a = b = ``error``; the screen's (:mod:`experiments.drop.screen`) a small b, since
calling an entry failing prunes its design, and a large a, since passing one only costs the
full verdict. An entry's decision is final: later drops from it count in the
verdict's numbers but not in its test. The design works when every entry works and fails as
soon as one fails; :mod:`experiments.drop.operating` computes what that does at any p exactly.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

WORKS, FAILS, UNDECIDED = "works", "fails", "undecided"


def short_of_working(decision: str | None) -> str:
    """What a decision other than ``works`` says of its design, for a sentence ("the optimum
    ... on its 4 fresh trials"): ``fails`` "does not work", ``undecided`` "is undecided (too
    few trials to tell whether it works at the target)", anything else "has no verdict".
    An undecided design is not one that does not work (issue 39)."""
    if decision == FAILS:
        return "does not work"
    if decision == UNDECIDED:
        return "is undecided (too few trials to tell whether it works at the target)"
    return "has no verdict"


@dataclass(frozen=True)
class Wald:
    """The test between ``works_p`` and ``fails_p`` (0 < fails_p < works_p < 1) with error
    rate ``error`` on each side, or ``false_works`` and ``false_fails`` when given."""

    works_p: float
    fails_p: float
    error: float = 0.01
    false_works: float | None = None  # a: P(works | fails_p); default ``error``
    false_fails: float | None = None  # b: P(fails | works_p); default ``error``

    @property
    def upper(self) -> float:
        """The LLR at or above which the entry works: ln((1 - b) / a)."""
        a, b = self._rates()
        return math.log((1.0 - b) / a)

    @property
    def lower(self) -> float:
        """The LLR at or below which the entry fails: ln(b / (1 - a))."""
        a, b = self._rates()
        return math.log(b / (1.0 - a))

    def _rates(self) -> tuple[float, float]:
        a = self.error if self.false_works is None else self.false_works
        b = self.error if self.false_fails is None else self.false_fails
        return a, b

    def llr(self, successes: int, drops: int) -> float:
        """The log-likelihood ratio of ``works_p`` over ``fails_p`` after ``drops`` drops
        with ``successes`` successes."""
        win = math.log(self.works_p / self.fails_p)
        loss = math.log((1.0 - self.works_p) / (1.0 - self.fails_p))
        return successes * win + (drops - successes) * loss

    def status(self, successes: int, drops: int) -> str:
        """``works``, ``fails`` or ``undecided`` for these counts (before any earlier
        crossing is taken into account: see :func:`advance`)."""
        value = self.llr(successes, drops)
        if value >= self.upper:
            return WORKS
        if value <= self.lower:
            return FAILS
        return UNDECIDED


def advance(
    test: Wald, statuses: Sequence[str], successes: Sequence[int], drops: int
) -> tuple[str, ...]:
    """Each entry's status after a look at ``drops`` drops: an entry already decided keeps
    its decision, an undecided one is judged on its ``successes`` now."""
    return tuple(
        s if s != UNDECIDED else test.status(k, drops)
        for s, k in zip(statuses, successes, strict=True)
    )


def design_decision(statuses: Sequence[str]) -> str:
    """The design's decision from its entries': fails as soon as one fails, works when all
    work, else undecided."""
    if FAILS in statuses:
        return FAILS
    if all(s == WORKS for s in statuses):
        return WORKS
    return UNDECIDED
