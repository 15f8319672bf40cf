"""The comparison's statistics: cost to solve, Dolan and Moré's performance profiles, their
area as one number per planner, its bootstrap over problems, and ECDFs.

E. D. Dolan and J. J. Moré (2002), "Benchmarking optimization software with performance
profiles", Math. Program. 91(2):201-213. For problem p and planner s with cost t(p, s), the
ratio is r(p, s) = t(p, s) / min_s' t(p, s') (infinite when s never solved p) and the
profile is rho_s(tau) = |{p : r(p, s) <= tau}| / |P|: the fraction of problems s solves
within a factor tau of the best planner on each. rho_s(1) is the fraction on which s is the
best; rho_s(tau) for large tau, the fraction it solves at all.

The cost of a sampling planner on a problem is a random variable; over n seeded runs it is
estimated by the expected propagations until the first success when runs are restarted
until one succeeds: the propagations of all runs (solved or not) over the number solved
(:func:`cost_to_solve`; infinite when no run solved). It rewards both speed and reliability.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np


def cost_to_solve(runs: Sequence[dict[str, Any]]) -> float:
    """Expected propagations to the first success with restarts: the sum of every run's
    propagations over the number of runs that solved (inf if none did)."""
    solved = sum(1 for r in runs if r["solved"])
    if solved == 0:
        return math.inf
    return float(sum(r["propagations"] for r in runs)) / solved


def ratio_matrix(costs: np.ndarray) -> np.ndarray:
    """Performance ratios of a (problems x planners) cost matrix, row by row: cost over the
    row's smallest cost; inf where the cost is inf. Rows where every cost is inf (no planner
    solved the problem) must be left out by the caller: their ratio is undefined."""
    costs = np.asarray(costs, dtype=float)
    best = costs.min(axis=1, keepdims=True)
    if not np.all(np.isfinite(best)):
        raise ValueError("a problem no planner solved has no performance ratios")
    if np.any(best <= 0):
        raise ValueError("costs must be positive")
    return costs / best


def profile(ratios: np.ndarray, taus: Sequence[float]) -> np.ndarray:
    """rho_s(tau) for each planner (column) at each tau: (len(taus) x planners)."""
    ratios = np.asarray(ratios, dtype=float)
    return np.array([(ratios <= tau).mean(axis=0) for tau in taus])


def horizon(ratios: np.ndarray) -> float:
    """log2 of the largest finite ratio, at least 1: the profile's right end, tau_max = 2^L."""
    finite = np.asarray(ratios, dtype=float)[np.isfinite(ratios)]
    return max(1.0, float(np.log2(finite.max()))) if finite.size else 1.0


def profile_area(ratios: np.ndarray, log2_max: float) -> np.ndarray:
    """Per planner, the area under rho_s over log2(tau) in [0, log2_max], over log2_max (1: best
    on every problem; 0: solved none within the horizon). rho_s is a step function, so the
    area is the mean over problems of max(0, 1 - log2 r(p, s) / log2_max)."""
    ratios = np.asarray(ratios, dtype=float)
    with np.errstate(divide="ignore"):
        logs = np.log2(ratios)
    share = np.where(np.isfinite(logs), np.clip(1.0 - logs / log2_max, 0.0, 1.0), 0.0)
    return share.mean(axis=0)


def bootstrap_best(
    ratios: np.ndarray, log2_max: float, resamples: int, seed: int
) -> dict[str, np.ndarray]:
    """The profile area's bootstrap over problems (resampled with replacement, ``seed``):
    each planner's area on the problems as they are (``area``), its 95% percentile interval
    (``low``, ``high``) and the share of resamples in which it has the largest area
    (``best_share``; a tie shares the resample equally)."""
    ratios = np.asarray(ratios, dtype=float)
    n, planners = ratios.shape
    rng = np.random.default_rng(seed)
    with np.errstate(divide="ignore"):
        logs = np.log2(ratios)
    share = np.where(np.isfinite(logs), np.clip(1.0 - logs / log2_max, 0.0, 1.0), 0.0)
    areas = np.empty((resamples, planners))
    for b in range(resamples):
        areas[b] = share[rng.integers(0, n, n)].mean(axis=0)
    top = areas.max(axis=1, keepdims=True)
    ties = np.isclose(areas, top, rtol=0.0, atol=1e-12)
    best_share = (ties / ties.sum(axis=1, keepdims=True)).mean(axis=0)
    low, high = np.percentile(areas, [2.5, 97.5], axis=0)
    return {"area": share.mean(axis=0), "low": low, "high": high, "best_share": best_share}


def ecdf(solved_costs: Sequence[float], total: int) -> tuple[list[float], list[float]]:
    """Steps of the fraction of ``total`` runs solved within x propagations: the sorted
    ``solved_costs`` (propagations of the runs that solved) and the fraction at each."""
    if total < len(solved_costs):
        raise ValueError("more solved runs than runs")
    xs = sorted(float(c) for c in solved_costs)
    return xs, [(k + 1) / total for k in range(len(xs))]
