"""The screen replayed against a pool of simulated drops (issue 36): its error rate over many
seeds without re-running the simulation.

The screen (:func:`experiments.drop.screen.run_sequence`) decides from the outcomes of the
drops it sees and nothing else: a success, a failure or a simulation fault per drop of an
entry. A pool of a design's perturbed drops, each simulated once at the screen's step and
once at the verdict's on the same draw (the same made feeder, friction and entry noise), is
a sample of the joint distribution of the two outcomes; a screen with another seed is then a
screen whose drops are drawn from the pool (with replacement, each entry from its own
column), each draw's fine outcome at hand when the screen confirms a failure on it. Over
1,000 seeds the fraction that fail the design estimates the screen's false-fail rate for a
design whose per-entry p at the verdict's step is the pool's (a bootstrap of the design:
as good as the pool is large).

Outcomes are strings, one character a draw: ``1`` success, ``0`` failure, ``x`` fault.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.stats import binomtest

from experiments.drop.screen import ScreenRun, run_sequence, screen_decision, wald_of
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.sequential import FAILS

OUTCOME = {"1": True, "0": False, "x": None}


@dataclass(frozen=True)
class EntryPool:
    """One entry's paired drops: ``coarse[i]`` and ``fine[i]`` are draw i's outcomes at the
    screen's step and at the verdict's (strings of ``1``, ``0``, ``x``)."""

    coarse: str
    fine: str

    def __post_init__(self) -> None:
        if len(self.coarse) != len(self.fine) or not self.coarse:
            raise ValueError(
                f"an entry's pool needs as many coarse as fine outcomes, at least one "
                f"(got {len(self.coarse)} and {len(self.fine)})"
            )
        if set(self.coarse + self.fine) - set(OUTCOME):
            raise ValueError("pool outcomes are '1' (success), '0' (failure) or 'x' (fault)")


def resampled_screen(
    pools: Sequence[EntryPool], settings: ScreenSettings, rng: np.random.Generator
) -> ScreenRun:
    """One screen of a design whose entries' drops are ``pools``: each drop a draw from its
    entry's pool (uniform, with replacement); a confirmation at the fine step
    (``settings.confirm_step``) reads the same draw's fine outcome."""
    rows: dict[int, int] = {}  # the screen's draw index -> the pool's row

    def row(k: int, index: int) -> int:
        if index not in rows:
            rows[index] = int(rng.integers(len(pools[k].coarse)))
        return rows[index]

    def coarse(k: int, index: int) -> bool | None:
        return OUTCOME[pools[k].coarse[row(k, index)]]

    def fine(k: int, index: int) -> bool | None:
        return OUTCOME[pools[k].fine[row(k, index)]]

    confirm = None if settings.confirm_step is None else fine
    return run_sequence(
        wald_of(settings), len(pools), settings.max_drops, coarse, confirm, settings.first_entry
    )


@dataclass(frozen=True)
class ResampledRate:
    """Over ``seeds`` resampled screens: how many failed the design, with the Clopper-Pearson
    95% interval of the rate; the mean coarse and fine drops a screen ran."""

    seeds: int
    fails: int
    ci: tuple[float, float]
    mean_coarse_drops: float
    mean_fine_drops: float

    @property
    def rate(self) -> float:
        return self.fails / self.seeds


def false_fail_rate(
    pools: Sequence[EntryPool], settings: ScreenSettings, seeds: int = 1000, seed: int = 0
) -> ResampledRate:
    """The fraction of ``seeds`` resampled screens (:func:`resampled_screen`, generators
    seeded ``seed``, ``seed + 1``, ...) that fail the design."""
    fails = coarse = fine = 0
    for s in range(seed, seed + seeds):
        run = resampled_screen(pools, settings, np.random.default_rng(s))
        fails += screen_decision(run.statuses) == FAILS
        coarse += run.coarse_drops
        fine += run.fine_drops
    ci = binomtest(fails, seeds).proportion_ci(0.95, method="exact")
    return ResampledRate(seeds, fails, (ci.low, ci.high), coarse / seeds, fine / seeds)


@dataclass(frozen=True)
class PairedShift:
    """The paired comparison of one entry's outcomes at the two steps over the draws that
    did not fault at either: n draws, successes at each step, the discordant pairs (success
    only at the coarse step, only at the fine) and McNemar's exact two-sided p-value."""

    n: int
    coarse_successes: int
    fine_successes: int
    coarse_only: int
    fine_only: int
    p_value: float

    @property
    def shift(self) -> float:
        """p at the coarse step minus p at the fine (negative: the coarse step fails more)."""
        return (self.coarse_successes - self.fine_successes) / self.n if self.n else math.nan


def paired_shift(pool: EntryPool) -> PairedShift:
    """:class:`PairedShift` of ``pool``."""
    pairs = [(c, f) for c, f in zip(pool.coarse, pool.fine, strict=True) if "x" not in (c, f)]
    coarse_only = sum(1 for c, f in pairs if c == "1" and f == "0")
    fine_only = sum(1 for c, f in pairs if c == "0" and f == "1")
    discordant = coarse_only + fine_only
    p = binomtest(coarse_only, discordant).pvalue if discordant else 1.0
    return PairedShift(
        len(pairs),
        sum(1 for c, _ in pairs if c == "1"),
        sum(1 for _, f in pairs if f == "1"),
        coarse_only,
        fine_only,
        float(p),
    )
