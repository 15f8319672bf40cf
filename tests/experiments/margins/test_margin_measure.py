"""P(both) at a value uses common random numbers: every value of an axis sees the same seeded
draws, with only the axis varied exact; the same seed gives the same margins; on a real axis
the ends meet the full rule and the cost counts every trial made; a design that does not
work gets none."""

from __future__ import annotations

import dataclasses

import pytest

from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import run_trial
from experiments.margins.axes import axes
from experiments.margins.measure import (
    AxisJob,
    MarginSettings,
    Subject,
    estimate,
    made_at,
    measure_axis,
)
from experiments.margins.run import margins_of, margins_of_each
from experiments.margins.search import required
from feeders.design import PARAMETER_NAMES
from feeders.scene_spec import design_scene

AXES = {a.name: a for a in axes()}


@pytest.fixture(scope="module")
def table3() -> Subject:
    return Subject.of_scene(design_scene("table3"))


def test_the_subject_recovers_the_default_part(table3):
    assert (table3.length, table3.width, table3.heavy_fraction) == pytest.approx((2.2, 0.7, 0.9))


@pytest.mark.parametrize("value", [0.76, 0.79])
def test_a_design_axis_is_exact_and_every_other_perturbation_is_the_verdicts(table3, value):
    d = draw(Perturbations(), seed=7, index=3)
    scene = made_at(table3, AXES["c"], value)(d)
    assert scene.design.c == value  # no manufacturing factor on the axis varied
    for k, name in enumerate(PARAMETER_NAMES):
        if name != "c":
            assert getattr(scene.design, name) == pytest.approx(
                getattr(table3.design, name) * d.design_factors[k]
            )
    assert scene.friction == pytest.approx(table3.friction * d.friction_factor)


def test_friction_is_exact_at_the_value(table3):
    d = draw(Perturbations(), seed=7, index=3)
    assert made_at(table3, AXES["mu"], 0.12)(d).friction == 0.12
    assert made_at(table3, AXES["mu"], 0.2)(d).design == made_at(table3, AXES["mu"], 0.12)(d).design


def test_a_part_axis_changes_the_part_only(table3):
    d = draw(Perturbations(), seed=1, index=0)
    long = made_at(table3, AXES["length"], 2.4)(d)
    short = made_at(table3, AXES["length"], 2.0)(d)
    assert (long.part.length, short.part.length) == (2.4, 2.0)
    assert long.design == short.design and long.friction == short.friction


def test_the_same_seed_gives_the_same_estimate_and_margin(table3):
    settings = MarginSettings(drops=3, seed=5)
    assert estimate(table3, AXES["theta"], 0.5, settings) == estimate(
        table3, AXES["theta"], 0.5, settings
    )
    job = AxisJob(table3, AXES["r"], settings)
    first, second = measure_axis(job), measure_axis(job)
    assert first.interval == second.interval
    assert [e.successes for e in first.high.evaluations] == [
        e.successes for e in second.high.evaluations
    ]
    lo, hi = first.box
    assert lo <= first.interval[0] <= table3.design.r <= first.interval[1] <= hi


def test_a_margin_is_the_same_every_time(table3):
    """The same seed gives the same margin, every estimate alike (the search is sequential
    within an axis's job, so the number of workers cannot change it)."""
    job = AxisJob(table3, AXES["theta"], MarginSettings(drops=6, seed=2))
    first, second = measure_axis(job), measure_axis(job)
    assert (first.nominal, first.low, first.high) == (second.nominal, second.low, second.high)


def test_the_ends_meet_the_full_rule_and_every_trial_made_is_counted(table3, monkeypatch):
    """On a real axis: each end reported inside has all its N trials counted and enough
    successes, each first outside failed the rule; the nominal is a look of one trial; the
    margin's cost is every trial made (faults aside)."""
    import experiments.margins.measure as measure

    made = []

    def counted(*args, **kwargs):
        trial = run_trial(*args, **kwargs)
        made.append(trial.fault)
        return trial

    monkeypatch.setattr(measure, "run_trial", counted)
    settings = MarginSettings(drops=6, seed=1)
    margin = measure_axis(AxisJob(table3, AXES["theta"], settings))
    assert margin.interval is not None
    assert (margin.nominal.successes, margin.nominal.drops, margin.nominal.planned) == (1, 1, 1)
    for side in (margin.low, margin.high):
        assert side.inside.drops == side.inside.planned == 6
        assert side.inside.successes >= required(settings.target, 6)
        if side.outside is not None:
            assert side.outside.planned == 6 and side.outside.failed(settings.target)
    assert margin.drops == made.count(False)


def test_a_design_that_does_not_work_gets_no_margins():
    subject = Subject.of_scene(design_scene("fig7a"))
    report = margins_of(subject, MarginSettings(drops=5), workers=1)
    assert report.verdict.decision == "fails"
    assert report.margins == ()
    data = report.to_dict()
    assert data["works"] is False and data["margins"] == []


def test_the_axes_of_a_design_that_does_not_work_are_reported_as_skipped():
    """``on_skip`` hears of every axis not measured, so a progress bar's total stays true."""
    subject = Subject.of_scene(design_scene("fig7a"))
    skipped: list[tuple[str, int]] = []
    reports = margins_of_each(
        {"fig7a": subject}, MarginSettings(drops=5), on_skip=lambda *a: skipped.append(a)
    )
    assert reports["fig7a"].margins == ()
    assert skipped == [("fig7a", len(axes()))]


def test_an_axis_below_the_target_at_nominal_has_no_interval(table3):
    """At an unreachable target the nominal fails and no search is made."""
    settings = dataclasses.replace(MarginSettings(drops=2), target=1.0)
    subject = dataclasses.replace(table3, friction=0.3)  # table3 fails at mu 0.3
    margin = measure_axis(AxisJob(subject, AXES["a"], settings))
    assert margin.interval is None and margin.low is None and margin.high is None
