"""The paired exact test a recommendation rests on, against scipy's binomial test (the
reference: McNemar's exact test is a one-sided binomial test on the discordant pairs)."""

from __future__ import annotations

import pytest
from scipy.stats import binomtest

from experiments.proportions import paired_exact_p, wilson_interval


@pytest.mark.parametrize(("first", "second"), [(0, 0), (1, 0), (5, 0), (3, 1), (7, 2), (0, 6)])
def test_paired_exact_p_is_mcnemars_exact_one_sided_test(first, second):
    n = first + second
    expected = 1.0 if n == 0 else binomtest(first, n, 0.5, alternative="greater").pvalue
    assert paired_exact_p(first, second) == pytest.approx(expected, rel=1e-12)


def test_five_discordant_draws_all_one_way_are_significant_at_five_percent():
    assert paired_exact_p(5, 0) < 0.05 <= paired_exact_p(4, 0)


def test_the_wilson_interval_holds_the_observed_fraction_exactly():
    """Regression (the wheel smoke's `planners --quick --runs 1`): at 0 of 7 the interval's
    lower end was 2.8e-17 above the fraction 0, and at 10 of 10 its upper end 1.1e-16 below 1,
    so matplotlib refused the error bar's negative arm. Reference: the definition, an
    interval around the point estimate k/n (0 and 1 exactly at k = 0 and k = n)."""
    for n in range(1, 200):
        for k in range(n + 1):
            lo, hi = wilson_interval(k, n)
            assert lo <= k / n <= hi
        assert wilson_interval(0, n)[0] == 0.0 and wilson_interval(n, n)[1] == 1.0
