"""Margins of a device family's design (issue 24): its axes are its parameters over its own
box and the walls' mu (no part axes); trial i at a value is the family verdict's trial i with
only the axis varied set exactly; a tiny run on fig1-cup's optimum brackets each side.

The design is fig1-cup's optimum as the optimiser found it (P(both) 120/120 on its fresh
draws)."""

from __future__ import annotations

import dataclasses
import pickle

import pytest

from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.perturbations import DropDraw, Perturbations, draw, toleranced_values
from experiments.drop.verdict import UNBUILDABLE, run_trial
from experiments.margins.axes import DESIGN, FAMILY_BOX, FRICTION, axes, family_axes
from experiments.margins.measure import (
    AxisJob,
    FamilySubject,
    MarginSettings,
    estimate,
    made_at,
    measure_axis,
)
from experiments.margins.run import axes_of
from feeders.device_family import load_family, packaged_family
from feeders.scene import Scene

OPTIMUM = (0.6907, 1.2855, 1.2213, 1.8129, 1.1795, 0.5437, 0.1447, 0.4392)
SEED = 3


@pytest.fixture(scope="module")
def cup() -> FamilySubject:
    path = packaged_family("fig1-cup")
    assert path is not None
    return FamilySubject.of_family(load_family(path), path.read_text(), OPTIMUM)


def _same_scene(a: Scene, b: Scene) -> bool:
    """Scenes hold arrays (no ``==``): equal when their pickles are byte for byte equal."""
    return pickle.dumps(a) == pickle.dumps(b)


def _with_factor_one(d: DropDraw, k: int) -> DropDraw:
    factors = list(d.design_factors)
    factors[k] = 1.0
    return dataclasses.replace(d, design_factors=tuple(factors))


def test_a_familys_axes_are_its_parameters_over_its_box_then_mu(cup):
    family = cup.family()
    found = family_axes(family)
    low, high = family.bounds()
    assert [a.name for a in found] == [*family.vector_names, "mu"]
    for axis, lo, hi in zip(found, low, high, strict=False):
        assert (axis.kind, axis.source, axis.low, axis.high) == (DESIGN, FAMILY_BOX, lo, hi)
    assert found[-1] == next(a for a in axes() if a.kind == FRICTION)  # the feeder's mu axis
    assert axes_of(cup) == found
    assert [cup.value(a) for a in found] == [*OPTIMUM, family.friction]


def test_the_subject_is_plain_data_and_refuses_another_familys_text(cup):
    assert pickle.loads(pickle.dumps(cup)) == cup
    assert cup.entries == entry_names(cup.family()) and cup.parameters == 8
    other = packaged_family("fig1")
    assert other is not None
    with pytest.raises(ValueError, match="not the family fig1-cup's"):
        FamilySubject.of_family(cup.family(), other.read_text(), OPTIMUM)


@pytest.mark.parametrize("index", [0, 5])
@pytest.mark.parametrize("name", ["theta", "pin_r"])
def test_at_the_designs_own_value_a_trial_is_the_verdicts_with_that_factor_one(cup, name, index):
    """Exactly checkable: the device made for draw i (the verdict's draw i: the same seed,
    entries and factor count) is the family verdict's device for that draw with the axis's
    factor set to 1, and so is the trial dropped in it. (The verdict's own trial i has that
    factor too, so it is not the same trial.)"""
    family = cup.family()
    k = family.vector_names.index(name)
    axis = next(a for a in axes_of(cup) if a.name == name)
    d = draw(Perturbations(), SEED, index, entries=2, parameters=8)
    verdict_make = made_devices(family, OPTIMUM)
    assert _same_scene(made_at(cup, axis, OPTIMUM[k])(d), verdict_make(_with_factor_one(d, k)))
    settings = MarginSettings().verdict_settings()
    margins_trial = run_trial(made_at(cup, axis, OPTIMUM[k]), cup.entries, settings, SEED, index, 8)

    def verdict_with_factor_one(drawn: DropDraw) -> Scene:
        return verdict_make(_with_factor_one(drawn, k))

    verdict_trial = run_trial(verdict_with_factor_one, cup.entries, settings, SEED, index, 8)
    assert margins_trial == verdict_trial


def test_away_from_the_nominal_only_the_axis_moves(cup):
    """At another value the device is the family built at the made values (each parameter
    times the draw's factor) with the axis's value exact; the walls' mu keeps its factor."""
    family = cup.family()
    k = family.vector_names.index("pin_dy")
    axis = next(a for a in axes_of(cup) if a.name == "pin_dy")
    d = draw(Perturbations(), SEED, 2, entries=2, parameters=8)
    made = list(toleranced_values(OPTIMUM, d.design_factors))
    made[k] = 0.8
    scene = made_at(cup, axis, 0.8)(d)
    expected = dataclasses.replace(family.build(made), friction=cup.friction * d.friction_factor)
    assert _same_scene(scene, expected)


def test_friction_is_exact_at_the_value_and_the_device_the_verdicts(cup):
    family = cup.family()
    mu = next(a for a in axes_of(cup) if a.kind == FRICTION)
    d = draw(Perturbations(), SEED, 4, entries=2, parameters=8)
    scene = made_at(cup, mu, 0.12)(d)
    assert scene.friction == 0.12
    verdict_scene = made_devices(family, OPTIMUM)(d)
    assert _same_scene(scene, dataclasses.replace(verdict_scene, friction=0.12))


def test_a_value_whose_device_cannot_be_built_fails_its_trials(cup):
    """pin_r = 1.5 (outside the box; the search never goes there) breaks the family's rules:
    every trial is refused as the verdict refuses an unbuildable made device, and the
    estimate stops once the target is out of reach."""
    pin_r = next(a for a in axes_of(cup) if a.name == "pin_r")
    settings = MarginSettings(drops=10)
    trial = run_trial(made_at(cup, pin_r, 1.5), cup.entries, settings.verdict_settings(), 0, 0, 8)
    assert trial.outcome == (UNBUILDABLE, UNBUILDABLE)
    e = estimate(cup, pin_r, 1.5, settings)
    assert (e.successes, e.drops, e.planned) == (0, 2, 10)
    assert not e.inside(settings.target)


@pytest.mark.parametrize("name", [pytest.param("pin_r", marks=pytest.mark.slow), "mu"])  # ~11 s
def test_a_tiny_run_brackets_each_side_within_the_box(cup, name):
    axis = next(a for a in axes_of(cup) if a.name == name)
    settings = MarginSettings(drops=4, seed=0)
    margin = measure_axis(AxisJob(cup, axis, settings))
    nominal = cup.value(axis)
    assert margin.nominal.inside(settings.target)  # 4 of 4 on these draws
    assert margin.low is not None and margin.high is not None
    box_low, box_high = margin.box
    assert box_low <= margin.low.limit <= nominal <= margin.high.limit <= box_high
    for side, edge in ((margin.low, box_low), (margin.high, box_high)):
        assert side.edge == edge
        if side.outside is None:  # the box's edge is inside
            assert side.limit == edge
        else:  # a bracket: last inside and first outside within the resolution
            assert not side.outside.inside(settings.target)
            assert abs(side.outside.value - side.limit) <= side.resolution + 1e-12
    assert measure_axis(AxisJob(cup, axis, settings)).interval == margin.interval
