"""A design against a baseline on the same fresh draws (issue 25's "Why this design"): the
draws are common to both designs, fresh (not the ranking's seed), and the parameter
differences are measured against Table 2's range."""

from __future__ import annotations

import pytest

from experiments.drop.compare import (
    compare_designs,
    fixed_settings,
    fresh_seed,
    parameter_differences,
)
from experiments.drop.verdict_settings import VerdictSettings
from experiments.sweep.job import verdict_seed
from feeders.design import PARAMETER_NAMES, PRESETS

SMALL = VerdictSettings(target=0.5, min_drops=2, batch=2, max_drops=4, t_max=4.0)


def test_a_design_compared_with_itself_gets_the_same_counts_on_the_same_draws() -> None:
    table3 = PRESETS["table3"]
    out = compare_designs({"same": table3}, ("table3", table3), SMALL, seed=11, drops=5)
    mine, base = out["designs"][0]["verdict"], out["baseline"]["verdict"]
    assert mine["drops"] == base["drops"] == 5  # a fixed sample, no early stop at min_drops
    assert mine["orientations"] == base["orientations"]
    assert mine["transitions"] == base["transitions"]
    assert out["designs"][0]["paired"] == {"draws": 5, "design_only": 0, "baseline_only": 0}
    assert all(d["difference"] == 0.0 for d in out["designs"][0]["differences"])


def test_another_seed_gives_other_draws() -> None:
    """The counterpart of the test above: equal counts come from equal draws, not from a
    verdict that ignores its seed (exit times of perturbed drops differ between seeds)."""
    table3 = PRESETS["table3"]
    a = compare_designs({}, ("table3", table3), SMALL, seed=11, drops=3)["baseline"]["verdict"]
    b = compare_designs({}, ("table3", table3), SMALL, seed=12, drops=3)["baseline"]["verdict"]
    times = [a["orientations"][o]["mean_exit_time_s"] for o in a["orientations"]]
    assert times != [b["orientations"][o]["mean_exit_time_s"] for o in b["orientations"]]


@pytest.mark.parametrize("sweep_seed", [0, 1, 12345])
def test_the_fresh_seed_is_none_of_the_seeds_the_designs_were_ranked_with(sweep_seed: int) -> None:
    ranked = [verdict_seed(sweep_seed, d) for d in range(64)]
    assert fresh_seed(sweep_seed, ranked) not in ranked
    assert fresh_seed(sweep_seed, ranked) == fresh_seed(sweep_seed, ranked)  # reproducible
    collide = fresh_seed(sweep_seed)
    assert fresh_seed(sweep_seed, [collide]) != collide


def test_the_fixed_settings_look_once_after_exactly_the_drops() -> None:
    fixed = fixed_settings(SMALL, 40)
    assert (fixed.min_drops, fixed.batch, fixed.max_drops) == (40, 40, 40)
    assert fixed.target == SMALL.target and fixed.perturbations == SMALL.perturbations


def test_the_parameter_differences_of_two_presets_as_fractions_of_table2() -> None:
    rows = parameter_differences(PRESETS["fig9"], PRESETS["table3"])
    assert [r["name"] for r in rows] == list(PARAMETER_NAMES)
    by = {r["name"]: r for r in rows}
    assert by["a"]["design"] == 1.2 and by["a"]["baseline"] == 1.1
    assert by["a"]["difference"] == pytest.approx(0.1)
    assert by["a"]["fraction"] == pytest.approx(1.0)  # Table 2: a in [1.1, 1.2]
    assert by["e"]["difference"] == pytest.approx(0.9)
    assert by["e"]["fraction"] == pytest.approx(0.9)  # e in [-2, -1]
    assert by["fy"]["difference"] == pytest.approx(2.5 - 1.0098)
    assert by["fy"]["fraction"] == pytest.approx((2.5 - 1.0098) / 2.0)  # fy in [0.5, 2.5]
    assert by["c"]["fraction"] == pytest.approx((0.8 - 0.7979) / 0.05)
