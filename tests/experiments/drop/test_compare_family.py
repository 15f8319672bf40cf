"""A device family's designs against a baseline on the same fresh draws (issue 24, "any
parametric device"): the comparison is one mechanism for every device. A family's design is
made per trial as its verdict makes it (made_devices), judged as its verdict judges it
(verdict_of), its differences measured on the family's box; the paper's feeder goes through
the same path as a family (FeederFamily) and its comparison stays its own verdicts, trial for
trial."""

from __future__ import annotations

import numpy as np
import pytest

from experiments.drop import compare
from experiments.drop.compare import (
    compare_designs,
    compare_family_designs,
    fixed_settings,
)
from experiments.drop.family_verdict import family_verdict, made_devices
from experiments.drop.perturbations import draw
from experiments.drop.verdict import design_verdict
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import PRESETS
from feeders.device_family import load_family, packaged_family
from feeders.feeder import DegenerateDesign
from feeders.feeder_family import FeederFamily
from feeders.part import Peg

SMALL = VerdictSettings(target=0.5, min_drops=2, batch=2, max_drops=4, t_max=4.0)
DROPS = 4
SEED = 21
FIG1 = load_family(packaged_family("fig1"))
# a fig1 design other than the default that builds (the default fails from open_leading)
OTHER = [0.31, 1.07, 1.39, -1.5, 0.45, 0.35]


def _timeless(verdict: dict) -> dict:
    return {k: v for k, v in verdict.items() if k != "wall_time_s"}


@pytest.fixture(scope="module")
def judged() -> tuple[dict, list]:
    """The comparison of OTHER with fig1's default, and what each of its verdicts was given
    and gave (the ``verdict_of`` calls: their device makers and verdicts)."""
    calls: list = []
    real = compare.verdict_of

    def spy(make_scene, orientations, settings, seed, parameters):
        verdict = real(make_scene, orientations, settings, seed, parameters)
        calls.append((make_scene, verdict))
        return verdict

    patch = pytest.MonkeyPatch()
    patch.setattr(compare, "verdict_of", spy)
    try:
        out = compare_family_designs(
            FIG1, {"other": OTHER}, ("default", FIG1.default()), SMALL, SEED, DROPS
        )
    finally:
        patch.undo()
    return out, calls


def test_its_verdicts_are_the_family_verdicts_on_the_same_seed(judged) -> None:
    out, calls = judged
    fixed = fixed_settings(SMALL, DROPS)
    for values, (_, verdict), shown in (
        (FIG1.default(), calls[0], out["baseline"]),
        (OTHER, calls[1], out["designs"][0]),
    ):
        reference = family_verdict(FIG1, values, fixed, SEED)
        assert verdict.trials == reference.trials  # trial for trial
        assert _timeless(shown["verdict"]) == _timeless(reference.to_dict())
        assert shown["verdict"]["drops"] == DROPS  # a fixed sample


def test_each_trial_makes_the_device_the_family_verdict_makes(judged) -> None:
    _, calls = judged
    for values, (make_scene, _) in zip((FIG1.default(), OTHER), calls, strict=True):
        reference = made_devices(FIG1, values)
        for index in range(DROPS):
            d = draw(SMALL.perturbations, SEED, index, entries=2, parameters=6)
            mine, theirs = make_scene(d), reference(d)
            assert mine.friction == theirs.friction
            assert np.array_equal(mine.obstacles.circles, theirs.obstacles.circles)
            for a, b in zip(mine.obstacles.polygons, theirs.obstacles.polygons, strict=True):
                assert np.array_equal(a, b)


def test_it_names_the_family_its_parameters_entries_and_baseline(judged) -> None:
    out, _ = judged
    assert out["family"] == "fig1" and out["parameters"] == list(FIG1.vector_names)
    assert out["entries"] == ["open_leading", "open_trailing"]
    assert out["baseline"]["label"] == "default"
    assert out["baseline"]["values"] == FIG1.default().tolist()
    assert (out["seed"], out["drops"], out["target"]) == (SEED, DROPS, SMALL.target)


def test_the_differences_are_fractions_of_the_familys_box(judged) -> None:
    out, _ = judged
    low, high = FIG1.bounds()
    rows = out["designs"][0]["differences"]
    assert [r["name"] for r in rows] == list(FIG1.vector_names)
    for row, x, y, lo, hi in zip(rows, OTHER, FIG1.default(), low, high, strict=True):
        assert (row["design"], row["baseline"]) == (x, y)
        assert row["fraction"] == pytest.approx((x - y) / (hi - lo))
        assert (row["low"], row["high"]) == (lo, hi)
    paired = out["designs"][0]["paired"]
    assert paired is not None and paired["draws"] == DROPS


def test_a_design_that_cannot_be_built_has_its_reason_and_a_foreign_vector_is_refused() -> None:
    blocked = dict(zip(FIG1.vector_names, FIG1.default(), strict=True))
    blocked.update(pin_x=0.0, pin_y=0.5)  # pin B over the mouth of exit chute C
    with pytest.raises(DegenerateDesign) as refused:
        FIG1.build(blocked)
    out = compare_family_designs(FIG1, {"blocked": blocked}, ("blocked", blocked), SMALL, 1, 2)
    assert out["baseline"]["verdict"] is None
    assert out["baseline"]["reason"] == refused.value.reason
    assert out["designs"][0]["paired"] is None
    with pytest.raises(ValueError, match="fig1: 3 values for 6 parameters"):
        compare_family_designs(
            FIG1, {"short": [1.0, 2.0, 3.0]}, ("default", FIG1.default()), SMALL, 1
        )


def test_the_feeders_comparison_is_its_own_verdicts_trial_for_trial() -> None:
    """The feeder's designs go through the same path (the feeder as a family); their
    verdicts are still design_verdict's, with the sweep's part and friction."""
    peg = Peg.two_density(length=2.0, width=0.6)
    fixed = fixed_settings(SMALL, 3)
    out = compare_designs(
        {"fig5a": PRESETS["fig5a"]}, ("table3", PRESETS["table3"]), SMALL, 5, 3, peg, 0.1
    )
    assert out["family"] is None and out["parameters"] == list(FeederFamily().vector_names)
    for name, shown in (("table3", out["baseline"]), ("fig5a", out["designs"][0])):
        theirs = design_verdict(PRESETS[name], peg, 0.1, fixed, seed=5)
        assert _timeless(shown["verdict"]) == _timeless(theirs.to_dict())
