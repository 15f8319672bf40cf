"""Outcome classes named by the part's orientations (issue 24): classify() names a drop in the
goal by the goal's class and one below the goal's top by its final yaw's class, the verdict's
transition matrix has the scene's classes as columns (success first), and the report counts
and colours the verdict's own success classes. The feeder's classes are what they were.

References: yaws placed by hand around the classes' centres; the peg family fig1 judged with
its classes renamed (same windows), whose trials must be the same drops under other names.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest
import yaml

from experiments.drop.family_verdict import family_verdict
from experiments.drop.outcomes import (
    FAILURE_CLASSES,
    HEAVY_DOWN,
    MISSED_GOAL,
    OUTCOMES,
    SIMULATION_FAULT,
    STOPPED,
    classify,
    outcome_classes,
)
from experiments.drop.verdict import CLASSES, UNBUILDABLE, Trial, Verdict, classes_of
from experiments.drop.verdict_settings import VerdictSettings
from experiments.report_kit.verdict_section import (
    SUCCESS_COLOUR,
    design_verdict_html,
    outcome_colour,
    outcome_order,
)
from feeders.design import PRESETS
from feeders.device_family import family_from_dict
from feeders.feeder import build_feeder
from feeders.scene import OTHER_ORIENTATION, Scene

FIG1 = Path(__file__).resolve().parents[3] / "feeders" / "families" / "fig1.yaml"
CUP_CLASSES = {
    "open end up": {"yaw": "-pi/2", "tolerance": "pi/4"},
    "on its side": {"yaw": [0, "pi"], "tolerance": "pi/4"},
    "open end down": {"yaw": "pi/2", "tolerance": "pi/4"},
}
GOAL_BOX = {"x": ["-exit_width/2", "exit_width/2"], "y": [-3.74, -2.2]}
IN_C = (0.0, -3.0)  # below the goal's top, inside exit chute C


def fig1_scene(**changes: Any) -> Scene:
    data = yaml.safe_load(FIG1.read_text())
    data.update(changes)
    family = family_from_dict(data)
    return family.build(family.default())


@pytest.fixture(scope="module")
def cup_scene() -> Scene:
    return fig1_scene(
        orientations=CUP_CLASSES, goal={**GOAL_BOX, "orientation": "open end up", "yaw_tol": 0.35}
    )


def test_a_drop_in_the_goal_is_the_goals_class(cup_scene: Scene) -> None:
    assert classify(cup_scene, "crossed", (*IN_C, -math.pi / 2 + 0.1), True) == "open end up"
    assert classify(cup_scene, "at_rest", (*IN_C, -math.pi / 2), True) == "open end up"


@pytest.mark.parametrize(
    "yaw, named",
    [
        (math.pi / 2, "open end down"),
        (math.pi / 2 - 0.6, "open end down"),
        (0.1, "on its side"),
        (-math.pi + 0.2, "on its side"),
        (-math.pi / 2 + 0.5, MISSED_GOAL),  # open end up, beyond the goal's 0.35: not a success
    ],
)
def test_a_crossing_that_failed_is_its_final_yaws_class(
    cup_scene: Scene, yaw: float, named: str
) -> None:
    assert classify(cup_scene, "crossed", (*IN_C, yaw), False) == named


def test_a_yaw_in_no_window_is_other_orientation() -> None:
    narrow = {"up": {"yaw": "-pi/2", "tolerance": 0.3}, "down": {"yaw": "pi/2", "tolerance": 0.3}}
    scene = fig1_scene(orientations=narrow, goal={**GOAL_BOX, "orientation": "up"})
    assert classify(scene, "crossed", (*IN_C, 0.0), False) == OTHER_ORIENTATION
    assert classify(scene, "crossed", (*IN_C, math.pi / 2 + 0.2), False) == "down"


def test_the_failures_that_are_not_orientations_keep_their_names(cup_scene: Scene) -> None:
    pose = (0.0, 1.0, 0.3)
    assert classify(cup_scene, "at_rest", pose, False) == STOPPED
    assert classify(cup_scene, "duration", pose, False) == "still moving at t_max"
    assert classify(cup_scene, "left_bounds", pose, False) == "left the bounds"
    assert classify(cup_scene, "inside_wall", pose, False) == SIMULATION_FAULT


def test_the_columns_are_the_scenes_classes_success_first(cup_scene: Scene) -> None:
    assert outcome_classes(cup_scene) == (
        "open end up",
        "on its side",
        "open end down",
        *FAILURE_CLASSES,
    )
    side = fig1_scene(orientations=CUP_CLASSES, goal={**GOAL_BOX, "orientation": "on its side"})
    assert outcome_classes(side)[:3] == ("on its side", "open end up", "open end down")
    assert classes_of(side)[1] == ("on its side",)


def test_the_feeders_classes_are_what_they_were() -> None:
    feeder = build_feeder(PRESETS["table3"])
    assert outcome_classes(feeder) == OUTCOMES
    assert classes_of(feeder) == (CLASSES, (HEAVY_DOWN,))
    assert OUTCOMES[:2] == ("heavy end down", "heavy end up")
    for yaw in (math.pi / 2, math.pi / 2 - 1.5, math.pi / 2 + 1.5):
        assert classify(feeder, "crossed", (0.0, -3.0, yaw), False) == "heavy end up"


def test_renaming_the_classes_renames_the_matrix_and_changes_no_drop() -> None:
    """fig1's default judged with the peg's classes and with the same windows renamed: the
    same trials, successes and times; the columns and counts under the new names."""
    settings = VerdictSettings(min_drops=3, batch=3, max_drops=3)
    data = yaml.safe_load(FIG1.read_text())
    peg = family_verdict(family_from_dict(data), _default(data), settings, 0)
    renamed_classes = {
        "closed end down": {"yaw": "-pi/2", "tolerance": "pi/2"},
        "closed end up": {"yaw": "pi/2", "tolerance": "pi/2"},
    }
    goal = {**GOAL_BOX, "orientation": "closed end down", "yaw_tol": 0.35}
    renamed = family_verdict(
        family_from_dict({**data, "orientations": renamed_classes, "goal": goal}),
        _default(data),
        settings,
        0,
    )
    names = {"heavy end down": "closed end down", "heavy end up": "closed end up"}
    assert [t.success for t in renamed.trials] == [t.success for t in peg.trials]
    assert [t.T for t in renamed.trials] == [t.T for t in peg.trials]
    assert [t.outcome for t in renamed.trials] == [
        tuple(names.get(c, c) for c in t.outcome) for t in peg.trials
    ]
    assert renamed.success_classes == ("closed end down",)
    for entry, row in renamed.transitions().items():
        assert list(row)[:2] == ["closed end down", "closed end up"]
        assert row["closed end down"] == renamed.successes(entry)
        assert list(row)[-1] == UNBUILDABLE
    assert renamed.to_dict()["success_classes"] == ["closed end down"]
    assert peg.classes[:2] == ("heavy end down", "heavy end up")


def _default(data: dict) -> list[float]:
    return [p["default"] for p in data["parameters"].values()]


def test_a_class_outside_the_columns_is_appended_when_a_drop_ends_in_it() -> None:
    trials = (
        Trial(0, (True, False), (HEAVY_DOWN, MISSED_GOAL), (1.0, 2.0)),
        Trial(1, (True, True), (HEAVY_DOWN, HEAVY_DOWN), (1.0, 2.0)),
    )
    verdict = Verdict(("a", "b"), trials, 0.9, "undecided", 0.0)
    matrix = verdict.transitions()
    assert list(matrix["a"]) == [*CLASSES, MISSED_GOAL]
    assert matrix["b"][MISSED_GOAL] == 1 and matrix["a"][MISSED_GOAL] == 0


CUP_VERDICT = {
    "decision": "fails",
    "drops": 10,
    "orientations": {
        "open_leading": {"successes": 2, "p": 0.2, "interval": [0.06, 0.51]},
        "open_trailing": {"successes": 9, "p": 0.9, "interval": [0.6, 0.98]},
    },
    "both": {"successes": 2, "p": 0.2, "interval": [0.06, 0.51]},
    "transitions": {
        "open_leading": {"open end up": 2, "stopped in the cavity": 3, "open end down": 5},
        "open_trailing": {"open end up": 9, "on its side": 1},
    },
    "success_classes": ["open end up"],
}


def test_the_report_counts_the_verdicts_own_success_class_over_its_own_entries() -> None:
    page = "\n".join(design_verdict_html({"design_id": 3, "verdict": CUP_VERDICT}, {}))
    assert "open leading" in page and "open trailing" in page
    assert "heavy" not in page
    assert "parts out open end up / parts in" in page and "0.550" in page  # 11 of 20
    header = page[page.index("<th>open end up</th>") :]
    assert header.index("open end up") < header.index("open end down")
    assert header.index("open end down") < header.index("stopped in the cavity")
    assert header.index("on its side") < header.index("stopped in the cavity")


def test_success_is_green_whatever_its_name_and_heavy_end_down_is_not_when_it_fails() -> None:
    assert outcome_colour("open end up", ("open end up",)) == SUCCESS_COLOUR
    assert outcome_colour(HEAVY_DOWN) == SUCCESS_COLOUR
    assert outcome_colour(HEAVY_DOWN, ("heavy end up",)) != SUCCESS_COLOUR
    assert outcome_colour("open end down", ("open end up",)) != SUCCESS_COLOUR
    assert outcome_colour("open end down", ("open end up",)) == outcome_colour("open end down")
    matrix = CUP_VERDICT["transitions"]
    assert outcome_order(matrix, ("open end up",))[0] == "open end up"
    assert outcome_order({"a": {"heavy end up": 1, HEAVY_DOWN: 2}}) == [HEAVY_DOWN, "heavy end up"]
