"""Confidence intervals for the proportions a sweep reports (feasible fractions, precision,
recall): few trials, values near 0 or 1, so not the normal approximation."""

from __future__ import annotations

import math

Z95 = 1.959963984540054  # two-sided 95% quantile of the standard normal


def wilson_interval(successes: int, trials: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval for a binomial proportion (95% for the default ``z``).

    E. B. Wilson (1927), "Probable inference, the law of succession, and statistical
    inference", J. Am. Stat. Assoc. 22(158):209-212. With p = k/n:
    centre = (p + z^2/(2n)) / (1 + z^2/n),
    half-width = z / (1 + z^2/n) * sqrt(p(1-p)/n + z^2/(4n^2)).
    Unlike p +- z sqrt(p(1-p)/n) it stays inside [0, 1] and is not empty at k = 0 or k = n,
    which matters for fractions near 0 or 1 on a few hundred designs. No trials: (0, 1).
    """
    if trials < 0 or not 0 <= successes <= trials:
        raise ValueError(f"need 0 <= successes <= trials, got {successes} of {trials}")
    if trials == 0:
        return 0.0, 1.0
    p = successes / trials
    z2 = z * z
    denominator = 1.0 + z2 / trials
    centre = (p + z2 / (2 * trials)) / denominator
    half = z / denominator * math.sqrt(p * (1 - p) / trials + z2 / (4 * trials * trials))
    # the interval holds p itself: at k = 0 and k = n centre -+ half is 0 and 1 only to
    # round-off (2.8e-17 above 0 at 0 of 7), and a figure's error bar refuses negative arms
    return min(p, max(0.0, centre - half)), max(p, min(1.0, centre + half))


def paired_exact_p(only_first: int, only_second: int) -> float:
    """One-sided exact McNemar test on paired trials (the same draws): the probability, if
    the two were equally reliable, of the first succeeding alone on at least ``only_first``
    of the ``only_first + only_second`` discordant draws, P(Binomial(n, 1/2) >= k).

    McNemar (1947), "Note on the sampling error of the difference between correlated
    proportions or percentages", Psychometrika 12(2):153-157; the exact (binomial) form is
    the one for few discordant pairs. No discordant draw: 1.0 (no evidence either way).
    """
    if only_first < 0 or only_second < 0:
        raise ValueError(f"need counts >= 0, got {only_first} and {only_second}")
    n = only_first + only_second
    return sum(math.comb(n, i) for i in range(only_first, n + 1)) / 2.0**n
