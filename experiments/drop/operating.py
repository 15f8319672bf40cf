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

from dataclasses import dataclass

import numpy as np
from scipy.stats import binom

from experiments.drop.verdict import VerdictSettings, decide, looks


@dataclass(frozen=True)
class OperatingPoint:
    """At true success probability ``p``: P(works), P(fails), P(undecided) and the expected
    number of trials of one verdict."""

    p: float
    works: float
    fails: float
    undecided: float
    mean_trials: float


def operating_point(p: float, settings: VerdictSettings) -> OperatingPoint:
    """The exact operating characteristic of the verdict's sequential test at ``p``."""
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"p = {p!r} is outside the allowed range [0, 1]")
    alive = np.array([1.0])  # P(count = k and still undecided), k = 0..n
    n = 0
    works = fails = mean = 0.0
    for look in looks(settings):
        step = binom.pmf(np.arange(look - n + 1), look - n, p)
        alive = np.convolve(alive, step)
        n = look
        for k in range(n + 1):
            decision = decide([k], n, settings.target)
            if decision == "works":
                works += alive[k]
            elif decision == "fails":
                fails += alive[k]
            else:
                continue
            mean += n * alive[k]
            alive[k] = 0.0
    rest = float(alive.sum())
    return OperatingPoint(p, works, fails, rest, mean + n * rest)
