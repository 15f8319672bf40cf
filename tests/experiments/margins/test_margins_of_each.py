"""Several designs' margins in one warm pool, one design after the other: a design whose
robustness can no longer beat one measured before it in full is stopped after the axis that
shows it, and the answer does not depend on how many workers ran it (issue 34: ranking the
confirmed designs by robustness without measuring every axis of the ones that cannot win).

The designs are of ``data/pit.yaml`` (tests/experiments/margins/test_margins_closed_form.py):
a floor ``depth`` below the goal, whose margin ends at the resting height 0.66 in closed
form, so a design of depth 1.0 has robustness 0.34 and one of depth 0.8 has 0.14."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.margins.measure import FamilySubject, MarginSettings
from experiments.margins.robustness import robustness
from experiments.margins.run import margins_of, margins_of_each
from experiments.sweep.report_recommendation import outranked
from feeders.device_family import load_family

FIXTURE = Path(__file__).with_name("data") / "pit.yaml"
SETTINGS = MarginSettings(drops=10, seed=11, t_max=2.0)


def _subject(depth: float, name: str) -> FamilySubject:
    family = load_family(FIXTURE)
    return FamilySubject.of_family(family, FIXTURE.read_text(), [depth], name=name)


@pytest.fixture(scope="module")
def raced():
    subjects = {"deep": _subject(1.0, "deep"), "shallow": _subject(0.8, "shallow")}
    return {w: margins_of_each(subjects, SETTINGS, workers=w, stop=outranked) for w in (1, 2)}


def test_a_design_that_cannot_be_more_robust_is_stopped_after_its_tightest_axis(raced):
    reports = raced[1]
    deep, shallow = reports["deep"].to_dict(), reports["shallow"].to_dict()
    assert deep["stopped"] is None and [r["parameter"] for r in deep["margins"]] == [
        "depth",
        "mu",
    ]
    # depth is the deep design's tightest axis inside the box, so it goes first; its room
    # (0.14 against 0.34) ends the shallow design before mu is measured
    assert [r["parameter"] for r in shallow["margins"]] == ["depth"]
    assert "not above deep's" in shallow["stopped"]
    assert robustness(shallow).bracket[1] <= robustness(deep).value


def test_a_stopped_design_costs_less_than_measuring_it_whole(raced):
    whole = margins_of(_subject(0.8, "shallow"), SETTINGS)
    assert raced[1]["shallow"].trials < whole.trials
    # the axes it did measure are those of the whole measurement
    assert (
        raced[1]["shallow"].to_dict()["margins"][0]["interval"]
        == (whole.to_dict()["margins"][0]["interval"])
    )


def _timeless(report) -> dict:
    data = report.to_dict()
    rows = [{k: v for k, v in row.items() if k != "wall_time_s"} for row in data["margins"]]
    return {"margins": rows, "stopped": data["stopped"]}


def test_the_race_is_the_same_on_one_worker_and_on_two(raced):
    for label in ("deep", "shallow"):
        assert _timeless(raced[1][label]) == _timeless(raced[2][label])
    # two workers may have begun an axis of the stopped design: its trials are counted
    assert raced[2]["shallow"].trials >= raced[1]["shallow"].trials
    assert raced[2]["deep"].trials == raced[1]["deep"].trials


def test_the_first_design_is_never_stopped():
    subjects = {"shallow": _subject(0.8, "shallow"), "deep": _subject(1.0, "deep")}
    reports = margins_of_each(subjects, SETTINGS, workers=1, stop=outranked)
    assert reports["shallow"].stopped is None and reports["deep"].stopped is None
    assert len(reports["deep"].margins) == 2
