"""What the verdict's sequential test does for a given true success probability: its
operating characteristic, exactly.

An entry whose drops succeed independently with probability p gets "works", "fails" or
"undecided" from :func:`experiments.drop.verdict.verdict_of` with probabilities that follow
from the binomial distribution at each look (:func:`experiments.drop.verdict.looks`), and the
verdict stops after a number of trials whose mean follows too. Computed by propagating the
distribution of the success count from look to look and absorbing the counts that decide; a
design with two entries, one of them sure (p = 1), behaves as this single entry. Used to
choose ``target``, ``min_drops`` and ``batch``: how often a design that works at p = 0.95 is
called failing, and what a clearly failing design costs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.signal import convolve2d
from scipy.stats import binom

from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.sequential import FAILS, WORKS, Wald
from experiments.drop.verdict import VerdictSettings, decide, looks
from experiments.drop.verdict_settings import SPRT
from experiments.proportions import wilson_interval


@dataclass(frozen=True)
class OperatingPoint:
    """At true success probability ``p`` (of each entry, for a design): P(works),
    P(fails), P(undecided) and the expected number of trials of one verdict."""

    p: float
    works: float
    fails: float
    undecided: float
    mean_trials: float


@dataclass(frozen=True)
class EntryPath:
    """One entry's test at true ``p``: per look (``looks``), the probability that it is
    decided works / fails at that look; ``undecided`` is the rest."""

    looks: tuple[int, ...]
    works_at: np.ndarray
    fails_at: np.ndarray

    @property
    def undecided(self) -> float:
        return float(max(0.0, 1.0 - self.works_at.sum() - self.fails_at.sum()))


def _check(p: float) -> None:
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"p = {p!r} is outside the allowed range [0, 1]")


def entry_status(successes: int, drops: int, settings: VerdictSettings) -> str:
    """One entry's decision at a look, by the verdict's rule (the SPRT's before any earlier
    crossing: the path below absorbs a crossing at the look it happens)."""
    if settings.rule == SPRT:
        return Wald(settings.works_p, settings.fails_p, settings.error).status(successes, drops)
    return decide([successes], drops, settings.target)


def entry_path(p: float, settings: VerdictSettings) -> EntryPath:
    """The exact distribution of one entry's decision and the look it comes at: the
    distribution of the success count propagated from look to look (binomial steps), the
    counts that decide absorbed where they decide."""
    _check(p)
    return sequential_path(p, looks(settings), lambda k, n: entry_status(k, n, settings))


def sequential_path(p: float, at: Sequence[int], status: Callable[[int, int], str]) -> EntryPath:
    """:func:`entry_path` of any test that looks after the drop counts ``at`` and decides
    ``status(successes, drops)`` there."""
    alive = np.array([1.0])  # P(count = k and still undecided), k = 0..n
    works, fails = np.zeros(len(at)), np.zeros(len(at))
    n = 0
    for i, look in enumerate(at):
        step = binom.pmf(np.arange(look - n + 1), look - n, p)
        alive = np.convolve(alive, step)
        n = look
        for k in range(n + 1):
            decision = status(k, n)
            if decision == WORKS:
                works[i] += alive[k]
            elif decision == FAILS:
                fails[i] += alive[k]
            else:
                continue
            alive[k] = 0.0
    return EntryPath(tuple(at), works, fails)


def operating_point(p: float, settings: VerdictSettings) -> OperatingPoint:
    """The exact operating characteristic of the verdict at ``p`` for one entry (a design
    whose other entries are sure, p = 1, under the Wilson rule; see
    :func:`design_operating_point` for a design)."""
    path = entry_path(p, settings)
    at = np.array(path.looks, dtype=float)
    rest = path.undecided
    mean = float((path.works_at + path.fails_at) @ at) + at[-1] * rest
    return OperatingPoint(p, float(path.works_at.sum()), float(path.fails_at.sum()), rest, mean)


def design_operating_point(p: float, settings: VerdictSettings, entries: int = 2) -> OperatingPoint:
    """The exact operating characteristic of the whole verdict for a design whose
    ``entries`` (1 or 2) each succeed with probability ``p``, independently from drop to
    drop and from each other (the model; a trial's two drops share the made feeder and its
    friction, so real entries are positively correlated). Wilson: the joint count
    distribution over both entries, decided jointly at each look. SPRT: each entry's
    :func:`entry_path` combined: works when both work (at the later look), fails at the
    first look some entry fails."""
    _check(p)
    if entries == 1:
        return operating_point(p, settings)
    if entries != 2:
        raise ValueError(f"entries = {entries!r} must be 1 or 2")
    if settings.rule == SPRT:
        return _sprt_pair(p, settings)
    return _wilson_pair(p, settings)


def _sprt_pair(p: float, settings: VerdictSettings) -> OperatingPoint:
    path = entry_path(p, settings)
    at = np.array(path.looks, dtype=float)
    last = len(at) - 1
    w, f = path.works_at, path.fails_at
    idx = np.arange(len(at))
    works = float(w.sum() ** 2)
    mean = float(w @ (at[np.maximum.outer(idx, idx)]) @ w)
    # fails: the first look at which an entry fails, the other entry anywhere at or after
    # it (or decided works at any look, or undecided)
    fails = 0.0
    for i in idx:
        # P(min failing look = i): A fails at i and B does not fail before i, or the reverse
        other = 1.0 - f[:i].sum()  # B does not fail before look i
        both_at_i = f[i] * f[i]
        q = 2.0 * f[i] * other - both_at_i
        fails += q
        mean += q * at[i]
    undecided = max(0.0, 1.0 - works - fails)
    mean += undecided * at[last]
    return OperatingPoint(p, works, fails, undecided, mean)


def _wilson_pair(p: float, settings: VerdictSettings) -> OperatingPoint:
    at = looks(settings)
    alive = np.ones((1, 1))  # P(counts = (kA, kB) and still undecided)
    works = fails = mean = 0.0
    n = 0
    for look in at:
        step = binom.pmf(np.arange(look - n + 1), look - n, p)
        alive = convolve2d(alive, np.outer(step, step))
        n = look
        bounds = np.array([wilson_interval(k, n) for k in range(n + 1)])
        high = bounds[:, 0] > settings.target
        low = bounds[:, 1] < settings.target
        w_mask = np.outer(high, high)
        f_mask = np.logical_or.outer(low, low)
        w, f = float(alive[w_mask].sum()), float(alive[f_mask & ~w_mask].sum())
        works, fails, mean = works + w, fails + f, mean + n * (w + f)
        alive[w_mask | f_mask] = 0.0
    rest = float(alive.sum())
    return OperatingPoint(p, works, fails, rest, mean + n * rest)


@dataclass(frozen=True)
class ScreenPoint:
    """At true success probability ``p`` of every entry: the probability that the screen
    fails the design (prunes it), passes it, or stops undecided (``max_drops`` drops of an
    entry); the two last go on to the verdict."""

    p: float
    fails: float
    passes: float
    undecided: float


def screen_operating_point(p: float, settings: ScreenSettings, entries: int = 2) -> ScreenPoint:
    """The exact operating characteristic of the screen (:mod:`experiments.drop.screen`) at
    ``p``, entries independent. Each entry's test sees only its own drops, so which entry
    drops next changes the cost, not the outcome: the design fails when some entry's test
    would fail within ``max_drops`` drops (the screen stops at the first, and any other is
    cut short), passes when every entry's passes."""
    _check(p)
    from experiments.drop.screen import wald_of

    test = wald_of(settings)
    path = sequential_path(p, range(1, settings.max_drops + 1), test.status)
    fails_one, passes_one = float(path.fails_at.sum()), float(path.works_at.sum())
    fails = 1.0 - (1.0 - fails_one) ** entries
    passes = passes_one**entries
    return ScreenPoint(p, fails, passes, max(0.0, 1.0 - fails - passes))


def screened_operating_point(
    p: float, screen: ScreenSettings, settings: VerdictSettings, entries: int = 2
) -> OperatingPoint:
    """The operating characteristic of the screen followed by the verdict for what it does
    not fail (their drops drawn from independent seeds, as the sweep draws them): works when
    the screen does not fail the design and the verdict says it works. ``mean_trials`` is
    the verdict's, counted only when it runs (the screen's drops are cheaper and apart)."""
    first = screen_operating_point(p, screen, entries)
    then = design_operating_point(p, settings, entries)
    on = 1.0 - first.fails
    return OperatingPoint(
        p,
        on * then.works,
        first.fails + on * then.fails,
        on * then.undecided,
        on * then.mean_trials,
    )


def crossing_probability(p: float, settings: ScreenSettings) -> float:
    """The probability that one entry's walk, its drops succeeding with probability ``p``,
    reaches the screen test's lower bound within ``max_drops`` drops, its upper bound
    ignored (exact: the count distribution propagated drop by drop). With ``confirm_step``
    the screen fails an entry only when the walk of its drops at the confirmation step did
    so (:func:`experiments.drop.screen.run_sequence`), so this bounds the probability that
    the screen fails an entry whose p *at the verdict's step* is ``p``, whatever the
    screen's coarse step does to its drops."""
    _check(p)
    from experiments.drop.screen import wald_of

    test = wald_of(settings)

    def status(k: int, n: int) -> str:
        return FAILS if test.llr(k, n) <= test.lower else "undecided"

    return float(sequential_path(p, range(1, settings.max_drops + 1), status).fails_at.sum())


def screen_fails_at_verdict_p(
    p: float, settings: ScreenSettings, shift: float = 0.0, shifted: int = 1, entries: int = 2
) -> float:
    """The probability that the screen, as it runs, fails a design whose ``entries`` each
    succeed with probability ``p`` at the verdict's step, independently (each entry's
    drops are its own draws). With ``confirm_step``: at most 1 - (1 - c)^entries, c the
    :func:`crossing_probability` at ``p`` (whatever the coarse step does). Without: exact
    when ``shifted`` of the entries succeed with ``p - shift`` at the screen's step (a
    shift measured on paired draws, docs/verdict.md) and the others with ``p``."""
    _check(p)
    if settings.confirm_step is not None:
        return 1.0 - (1.0 - crossing_probability(p, settings)) ** entries
    one = screen_operating_point(p, settings, 1).fails
    low = screen_operating_point(max(0.0, p - shift), settings, 1).fails
    return 1.0 - (1.0 - low) ** shifted * (1.0 - one) ** (entries - shifted)
