"""The operating characteristic of the verdict's sequential tests (Wilson looks and Wald's
SPRT), against hand-worked fixed samples and Wald's bounds, and Monte Carlo runs of the
verdict's own loop with coin flips for drops."""

from __future__ import annotations

import numpy as np
import pytest

from experiments.drop.operating import design_operating_point, operating_point
from experiments.drop.verdict import VerdictSettings, decide, looks
from experiments.proportions import wilson_interval


def test_looks_start_at_min_drops_step_by_batch_and_end_at_max_drops():
    assert looks(VerdictSettings(min_drops=10, batch=10, max_drops=35)) == [10, 20, 30, 35]
    assert looks(VerdictSettings(min_drops=4, batch=4, max_drops=4)) == [4]


def test_a_fixed_sample_of_40_works_only_when_all_40_succeed():
    """By hand (Wilson, z = 1.96): 40/40 has lower bound 0.912 > 0.9, 39/40 has 0.871; so
    with one look at 40 trials P(works) = p^40 exactly."""
    assert wilson_interval(40, 40)[0] > 0.9 > wilson_interval(39, 40)[0]
    settings = VerdictSettings(min_drops=40, batch=10, max_drops=40)
    for p in (0.9, 0.95, 0.99):
        point = operating_point(p, settings)
        assert point.works == pytest.approx(p**40, rel=1e-9)
        assert point.mean_trials == pytest.approx(40.0)
        assert point.works + point.fails + point.undecided == pytest.approx(1.0)


def test_the_exact_characteristic_matches_coin_flip_verdicts():
    """20,000 verdicts of the same test, each drop a coin with P(success) = p: the frequencies
    and the mean number of trials agree with the exact values within 4 standard errors."""
    settings = VerdictSettings()
    rng = np.random.default_rng(3)
    for p in (0.5, 0.9, 0.95):
        runs, outcomes, trials = 20_000, {"works": 0, "fails": 0, "undecided": 0}, []
        for _ in range(runs):
            k = n = 0
            decision = "undecided"
            for look in looks(settings):
                k += int(rng.binomial(look - n, p))
                n = look
                decision = decide([k], n, settings.target)
                if decision != "undecided":
                    break
            outcomes[decision] += 1
            trials.append(n)
        exact = operating_point(p, settings)
        for name in outcomes:
            q = getattr(exact, name)
            assert abs(outcomes[name] / runs - q) <= 4 * np.sqrt(q * (1 - q) / runs) + 1e-12
        sd = np.std(trials) / np.sqrt(runs)
        assert abs(np.mean(trials) - exact.mean_trials) <= 4 * sd + 1e-12


def test_a_clear_failure_costs_the_first_look_and_p_out_of_range_is_refused():
    settings = VerdictSettings()
    assert operating_point(0.0, settings).mean_trials == settings.min_drops
    assert operating_point(1.0, settings).works == pytest.approx(1.0)
    with pytest.raises(ValueError, match=r"p = 1\.5 .*\[0, 1\]"):
        operating_point(1.5, settings)


SPRT_SETTINGS = VerdictSettings(rule="sprt", min_drops=1, batch=1, max_drops=200)


def test_the_sprt_decides_a_sure_entry_at_walds_bounds():
    """By hand: ln(0.99/0.01) = 4.595; a failure adds ln(0.05/0.2) = -1.386 (4 failures
    cross, 3 do not) and a success ln(0.95/0.8) = 0.1719 (27 successes cross, 26 do not)."""
    assert operating_point(0.0, SPRT_SETTINGS).mean_trials == pytest.approx(4.0)
    assert operating_point(1.0, SPRT_SETTINGS).mean_trials == pytest.approx(27.0)
    assert operating_point(1.0, SPRT_SETTINGS).works == pytest.approx(1.0)


def test_a_fixed_sample_of_40_for_two_entries_works_only_when_all_80_drops_succeed():
    settings = VerdictSettings(min_drops=40, batch=10, max_drops=40)
    for p in (0.9, 0.97):
        point = design_operating_point(p, settings)
        assert point.works == pytest.approx(p**80, rel=1e-9)
        assert point.works + point.fails + point.undecided == pytest.approx(1.0)


def test_the_sprts_error_rates_hold_for_a_design_at_both_hypotheses():
    """Wald: each entry errs with probability about 0.01 at its hypothesis; a design of two
    entries fails if either does, so at p = 0.95 at most about twice that."""
    assert design_operating_point(0.8, SPRT_SETTINGS).works <= 0.01
    assert design_operating_point(0.95, SPRT_SETTINGS).fails <= 0.021


@pytest.mark.parametrize("settings", [VerdictSettings(), SPRT_SETTINGS], ids=["wilson", "sprt"])
@pytest.mark.slow  # ~40 s each; the exact characteristic's test stays
def test_the_design_characteristic_matches_the_verdicts_own_loop_on_coin_flips(
    settings, monkeypatch
):
    """1,500 verdicts through :func:`experiments.drop.verdict.verdict_of` itself, each drop
    a coin with P(success) = p for each entry independently: decisions and mean trials
    agree with the exact two-entry values within 4 standard errors."""
    from experiments.drop import verdict as verdict_module

    def coin_trial(_make, orientations, _settings, seed, index, _parameters=12):
        rng = np.random.default_rng([seed, index])
        success = tuple(bool(rng.random() < P) for _ in orientations)
        return verdict_module.Trial(index, success, ("x",) * 2, (1.0,) * 2)

    monkeypatch.setattr(verdict_module, "run_trial", coin_trial)
    for P in (0.85, 0.95):
        runs = 1_500
        verdicts = [
            verdict_module.verdict_of(None, ("a", "b"), settings, seed) for seed in range(runs)
        ]
        exact = design_operating_point(P, settings)
        for name in ("works", "fails", "undecided"):
            q = getattr(exact, name)
            seen = sum(v.decision == name for v in verdicts) / runs
            assert abs(seen - q) <= 4 * np.sqrt(q * (1 - q) / runs) + 1e-9, (P, name)
        trials = [v.drops for v in verdicts]
        assert abs(np.mean(trials) - exact.mean_trials) <= 4 * np.std(trials) / np.sqrt(runs)
