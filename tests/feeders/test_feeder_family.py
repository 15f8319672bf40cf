"""The paper's 12-parameter feeder is one device family (issue 24): its parameters, box and
entries are Table 2's and the feeder's, it builds the feeder's scenes, and the family's verdict
and screen (experiments.drop.family_verdict) are the feeder's own, trial for trial. The
reference is the feeder's code path (build_feeder, design_verdict, design_screen), which the
generalisation must leave unchanged."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from experiments.drop.family_verdict import (
    entry_names,
    family_screen,
    family_verdict,
    made_devices,
)
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.screen import design_screen
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.verdict import design_verdict, made_feeders
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import DESIGN_SPACE, PARAMETER_NAMES, PRESETS, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.feeder_family import FeederFamily
from feeders.halton import halton_points
from feeders.part import Peg

FEEDER = FeederFamily()


def test_its_parameters_box_default_and_entries_are_the_papers():
    assert FEEDER.vector_names == PARAMETER_NAMES
    low, high = FEEDER.bounds()
    assert np.array_equal(low, DESIGN_SPACE.low) and np.array_equal(high, DESIGN_SPACE.high)
    assert np.array_equal(FEEDER.default(), PRESETS["table3"].to_vector())
    assert entry_names(FEEDER) == ORIENTATIONS


def test_it_builds_the_feeders_scenes_and_refuses_what_the_feeder_refuses():
    for row in halton_points(20, seed=2):
        expected = build_feeder(DesignParameters.from_vector(row))
        scene = FEEDER.build(dict(zip(PARAMETER_NAMES, row, strict=True)))
        assert scene.starts == expected.starts and scene.goal == expected.goal
        for a, b in zip(scene.obstacles.polygons, expected.obstacles.polygons, strict=True):
            assert np.array_equal(a, b)
    narrow = dataclasses.replace(PRESETS["table3"], a=0.6)  # the peg is 0.7 wide
    with pytest.raises(DegenerateDesign) as theirs:
        build_feeder(narrow)
    with pytest.raises(DegenerateDesign) as mine:
        FEEDER.build(narrow.to_vector())
    assert mine.value.reason == theirs.value.reason


@pytest.mark.parametrize("design", ["table3", "fig5a"])
def test_its_verdict_is_the_feeders_trial_for_trial(design):
    settings = VerdictSettings(min_drops=4, batch=4, max_drops=8)
    values = PRESETS[design].to_vector()
    mine = family_verdict(FEEDER, values, settings, seed=3)
    theirs = design_verdict(PRESETS[design], settings=settings, seed=3)
    assert mine.trials == theirs.trials
    assert mine.decision == theirs.decision


def test_its_screen_is_the_feeders_and_a_part_and_friction_reach_every_trial():
    settings = ScreenSettings(max_drops=10)
    fig4 = PRESETS["fig4"]
    mine = family_screen(FEEDER, fig4.to_vector(), settings, seed=5)
    theirs = design_screen(fig4, settings=settings, seed=5)
    assert (mine.drops, mine.successes, mine.decision) == (
        theirs.drops,
        theirs.successes,
        theirs.decision,
    )
    peg = Peg.two_density(length=2.0, width=0.6)
    settings = VerdictSettings(min_drops=3, batch=3, max_drops=3)
    mine_v = family_verdict(FEEDER, fig4.to_vector(), settings, seed=1, part=peg, friction=0.1)
    theirs_v = design_verdict(fig4, part=peg, friction=0.1, settings=settings, seed=1)
    assert mine_v.trials == theirs_v.trials


def test_a_made_feeder_stays_within_what_can_be_built_as_the_verdicts_always_has():
    """A pin of radius 0.01, made up to 1% small, would be down to 0.0099; what can be built
    stops at 0.01 (PHYSICAL_BOUNDS): the family's made feeder keeps it there as made_feeders
    does."""
    tiny_pin = dataclasses.replace(PRESETS["table3"], r=0.01)
    mine = made_devices(FEEDER, tiny_pin.to_vector())
    theirs = made_feeders(tiny_pin)
    radii = set()
    for i in range(30):
        d = draw(Perturbations(), 4, i, 2)
        a, b = mine(d), theirs(d)
        assert np.array_equal(a.obstacles.circles, b.obstacles.circles)
        assert a.friction == b.friction
        radii.add(float(a.obstacles.circles[0, 2]))
    assert min(radii) == 0.01 and max(radii) > 0.01  # clamped below, free above
