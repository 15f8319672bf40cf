"""The paired exact test a recommendation rests on, against scipy's binomial test (the
reference: McNemar's exact test is a one-sided binomial test on the discordant pairs)."""

from __future__ import annotations

import pytest
from scipy.stats import binomtest

from experiments.proportions import paired_exact_p


@pytest.mark.parametrize(("first", "second"), [(0, 0), (1, 0), (5, 0), (3, 1), (7, 2), (0, 6)])
def test_paired_exact_p_is_mcnemars_exact_one_sided_test(first, second):
    n = first + second
    expected = 1.0 if n == 0 else binomtest(first, n, 0.5, alternative="greater").pvalue
    assert paired_exact_p(first, second) == pytest.approx(expected, rel=1e-12)


def test_five_discordant_draws_all_one_way_are_significant_at_five_percent():
    assert paired_exact_p(5, 0) < 0.05 <= paired_exact_p(4, 0)
