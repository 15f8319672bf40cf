"""Which entries the necessary conditions prove unsolvable, on the suite's own designs."""

from __future__ import annotations

from experiments.planner_comparison.designs import scene_for
from experiments.planner_comparison.unsolvable import (
    ONE_OF_TWO,
    OPEN,
    PROVEN,
    entry_statuses,
    necessary_status,
)

ENTRIES = ["heavy_leading", "heavy_trailing"]


def test_a_failed_corridor_proves_both_entries_unsolvable() -> None:
    assert {s for s, _ in entry_statuses("corridor", ENTRIES).values()} == {PROVEN}


def test_a_failed_turn_proves_only_the_heavy_trailing_entry_unsolvable() -> None:
    statuses = entry_statuses("turn", ENTRIES)
    assert statuses["heavy_trailing"][0] == PROVEN
    assert statuses["heavy_leading"][0] == OPEN


def test_a_failed_sliced_test_says_one_of_the_two() -> None:
    assert {s for s, _ in entry_statuses("sliced", ENTRIES).values()} == {ONE_OF_TWO}


def test_the_quick_suites_failing_halton_design_fails_the_turn_test() -> None:
    scene = scene_for({"halton": {"seed": 1, "index": 7}})
    status = necessary_status(scene, ENTRIES)
    assert status["tested"] and status["failed"] == "turn"
    assert status["entries"]["heavy_trailing"][0] == PROVEN


def test_table3_passes_and_a_familys_design_is_not_tested() -> None:
    table3 = necessary_status(scene_for({"preset": "table3"}), ENTRIES)
    assert table3["failed"] is None
    assert {s for s, _ in table3["entries"].values()} == {OPEN}
    cup = scene_for({"family": "fig1-cup"})
    status = necessary_status(cup, list(cup.starts))
    assert not status["tested"]
    assert {s for s, _ in status["entries"].values()} == {OPEN}
