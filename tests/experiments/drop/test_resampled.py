"""The screen replayed against a pool of paired drops (issue 36): the same loop, its drops
drawn from the pool. References: the exact operating characteristic (a pool of one
outcome is a coin of known p), hand-counted McNemar pairs and scipy's binomial test."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import binomtest

from experiments.drop.operating import screen_fails_at_verdict_p, screen_operating_point
from experiments.drop.resampled import (
    EntryPool,
    false_fail_rate,
    paired_shift,
    resampled_screen,
)
from experiments.drop.screen import screen_decision
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.sequential import FAILS


def test_a_pool_of_failures_fails_in_four_drops_and_one_of_successes_never():
    settings = ScreenSettings()
    never = EntryPool("1" * 10, "1" * 10)
    always = EntryPool("0" * 10, "0" * 10)
    run = resampled_screen([never, always], settings, np.random.default_rng(0))
    assert screen_decision(run.statuses) == FAILS and run.coarse_drops == 4
    assert false_fail_rate([never, never], settings, seeds=50).fails == 0


def test_the_resampled_rate_of_a_coin_pool_matches_the_exact_characteristic():
    """A pool of 9 successes and 1 failure per entry is a coin of p = 0.9 at the screen's
    step; 4,000 resampled screens fail the design as often as the exact characteristic says
    (within the rate's 95% Clopper-Pearson interval, widened to 99.9%)."""
    settings = ScreenSettings(works_p=0.95, fails_p=0.5, false_works=0.1)
    pool = EntryPool("1111111110", "1111111111")
    rate = false_fail_rate([pool, pool], settings, seeds=4000)
    exact = screen_operating_point(0.9, settings).fails
    low, high = binomtest(rate.fails, rate.seeds).proportion_ci(0.999, method="exact")
    assert low <= exact <= high
    assert rate.mean_fine_drops == 0.0 and rate.mean_coarse_drops > 2


def test_confirmation_reads_the_same_draws_fine_outcome():
    """Coarse drops all fail and their fine outcomes all succeed: confirmed, never failed."""
    settings = ScreenSettings(confirm_step=1e-3)
    pool = EntryPool("0000", "1111")
    rate = false_fail_rate([pool, pool], settings, seeds=20)
    assert rate.fails == 0 and rate.mean_fine_drops >= 4


def test_the_paired_shift_counts_the_discordant_draws_and_leaves_out_faults():
    # draws: (1,1) (1,0) (0,1) (0,1) (0,1) (x,1) (1,x) (0,0)
    shift = paired_shift(EntryPool("11000x10", "101111x0"))
    assert (shift.n, shift.coarse_only, shift.fine_only) == (6, 1, 3)
    assert shift.coarse_successes == 2 and shift.fine_successes == 4
    assert shift.shift == pytest.approx(-2 / 6)
    assert shift.p_value == pytest.approx(binomtest(1, 4).pvalue)


@pytest.mark.parametrize("coarse, fine", [("10", "1"), ("", ""), ("1a", "11")])
def test_a_bad_pool_is_refused(coarse, fine):
    with pytest.raises(ValueError, match="pool"):
        EntryPool(coarse, fine)


def test_a_pool_whose_coarse_step_loses_02_is_failed_as_the_shifted_characteristic_says():
    """Entry 0 succeeds at the fine step always and at the coarse step 8 times in 10; entry 1
    always: the design's rate at the verdict's p = 1 with one entry 0.2 lower at the screen's
    step (``screen_fails_at_verdict_p``), within the 99.9% interval of 6,000 screens."""
    settings = ScreenSettings()
    pools = [EntryPool("1111111100", "1111111111"), EntryPool("1" * 10, "1" * 10)]
    rate = false_fail_rate(pools, settings, seeds=6000)
    exact = screen_fails_at_verdict_p(1.0, settings, shift=0.2)
    low, high = binomtest(rate.fails, rate.seeds).proportion_ci(0.999, method="exact")
    assert low <= exact <= high
    assert exact > 0.002  # p = 0.8 at the screen's step: beyond what the default is built for
