"""Specification of a family's part (``part:``) and of orientation classes (issue 24): a scene's
named orientations (name -> yaw windows), goals that accept classes, and a family's
``orientations:`` and ``goal.orientation``.

References: the cup's mass and inertia from feeders.cup.cup_part (worked by hand in its own
tests), yaws placed by hand at and around the classes' centres, and the peg family fig1 (its
scenes unchanged when the classes are only renamed).
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from feeders.composite_part import CompositePart
from feeders.cup import cup_part
from feeders.design import PRESETS
from feeders.device_family import FamilyError, family_from_dict, load_family
from feeders.feeder import build_feeder
from feeders.part import Peg
from feeders.scene import (
    HEAVY_END_DOWN,
    HEAVY_END_UP,
    OTHER_ORIENTATION,
    PEG_ORIENTATIONS,
    Goal,
    OrientationClass,
    orientation_of,
)
from feeders.scene_yaml import SceneError, environment_from_dict, scene_from_dict

FIG1 = Path(__file__).resolve().parents[2] / "feeders" / "families" / "fig1.yaml"
QUARTER = math.pi / 4

CUP_CLASSES = {
    "open end up": {"yaw": "-pi/2", "tolerance": "pi/4"},
    "on its side": {"yaw": [0, "pi"], "tolerance": "pi/4"},
    "open end down": {"yaw": "pi/2", "tolerance": "pi/4"},
}


def fig1(**changes: Any) -> dict[str, Any]:
    data = yaml.safe_load(FIG1.read_text())
    data.update(copy.deepcopy(changes))
    return data


def cup_goal(**changes: Any) -> dict[str, Any]:
    goal = {"x": ["-exit_width/2", "exit_width/2"], "y": [-3.74, -2.2]}
    goal.update(changes)
    return goal


# --- part: ------------------------------------------------------------------------------


def test_a_family_part_may_be_the_packaged_cup_a_composite_part_or_the_peg() -> None:
    cup = environment_from_dict({"part": "cup"}, composite=True)["part"]
    reference = cup_part()
    assert isinstance(cup, CompositePart)
    assert cup.mass == pytest.approx(reference.mass) and cup.inertia == pytest.approx(
        reference.inertia
    )
    square = {"outline": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 2.0}
    plate = environment_from_dict({"part": square}, composite=True)["part"]
    assert isinstance(plate, CompositePart) and plate.mass == pytest.approx(2.0)
    peg = environment_from_dict({"part": {"length": 2.0, "width": 0.8}}, composite=True)["part"]
    assert isinstance(peg, Peg) and peg.length == 2.0


@pytest.mark.parametrize(
    "part, words",
    [
        ("mug", "part = 'mug': not a packaged part; packaged parts: cup"),
        ({"length": 2.0, "outline": [[0, 0], [1, 0], [1, 1]]}, "not both"),
        (
            {"outline": [[0, 0], [1, 1], [1, 0], [0, 1]], "density": 1.0},
            "part.outline: the outline intersects itself",
        ),
        ({"outline": [[0, 0], [1, 0], [2, 0]], "density": 1.0}, "the outline has zero area"),
        (
            {"pieces": [{"polygon": [[0, 0], [1, 0], [1, 1]], "density": 0.0}]},
            "part.pieces[0].density = 0.0 is outside the allowed range",
        ),
    ],
)
def test_a_bad_family_part_is_one_line_naming_the_file_and_field(
    tmp_path: Path, part: Any, words: str
) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(fig1(part=part), sort_keys=False))
    with pytest.raises(FamilyError) as error:
        load_family(path)
    message = str(error.value)
    assert "\n" not in message and message.startswith(str(path)) and words in message


def test_a_scene_file_still_takes_only_the_peg() -> None:
    """Scene files, configs and the 12-parameter feeder take the peg until the levels take
    composite parts: a composite part there is one line, not a traceback."""
    with pytest.raises(SceneError, match="part"):
        scene_from_dict({"feeder": {"preset": "table3"}, "part": "cup"})
    with pytest.raises(SceneError, match="unknown key"):
        environment_from_dict({"part": {"outline": [[0, 0], [1, 0], [1, 1]], "density": 1}})


def test_a_family_with_the_cup_builds_scenes_with_the_cup() -> None:
    family = family_from_dict(fig1(part="cup"))
    scene = family.build(family.default())
    assert isinstance(scene.part, CompositePart) and scene.part.mass == pytest.approx(1.0)


# --- orientation classes ----------------------------------------------------------------


def test_the_pegs_classes_cover_every_yaw_by_the_sign_of_its_sine() -> None:
    for yaw in np.linspace(-math.pi + 1e-3, math.pi - 1e-3, 101):
        expected = HEAVY_END_DOWN if math.sin(yaw) < 0 else HEAVY_END_UP
        if abs(math.sin(yaw)) > 1e-9:
            assert orientation_of(PEG_ORIENTATIONS, float(yaw)) == expected


def test_a_yaw_goes_to_the_nearest_centre_of_the_windows_that_hold_it() -> None:
    classes = (
        OrientationClass("open end up", (-math.pi / 2,), QUARTER),
        OrientationClass("on its side", (0.0, math.pi), QUARTER),
        OrientationClass("open end down", (math.pi / 2,), QUARTER),
    )
    assert orientation_of(classes, -math.pi / 2 + 0.3) == "open end up"
    assert orientation_of(classes, math.pi - 0.2) == "on its side"
    assert orientation_of(classes, -math.pi + 0.2) == "on its side"  # the same centre, wrapped
    assert orientation_of(classes, 0.2) == "on its side"
    assert orientation_of(classes, math.pi / 2 + 0.7) == "open end down"
    assert orientation_of(classes, -QUARTER) == "open end up"  # tie: the first listed
    wide = (OrientationClass("wide", (0.0,), 2.0), OrientationClass("narrow", (1.5,), 0.2))
    assert orientation_of(wide, 1.45) == "narrow"  # both hold it: the nearer centre
    assert orientation_of(wide, 1.8) == "wide"  # only the wide window holds it
    assert orientation_of(wide, -2.5) == OTHER_ORIENTATION


@pytest.mark.parametrize(
    "name, centres, tolerance",
    [
        ("", (0.0,), 1.0),
        (OTHER_ORIENTATION, (0.0,), 1.0),
        ("a", (), 1.0),
        ("a", (4.0,), 1.0),
        ("a", (0.0,), 0.0),
        ("a", (0.0,), 3.5),
    ],
)
def test_an_orientation_class_outside_its_ranges_is_refused(name, centres, tolerance) -> None:
    with pytest.raises(ValueError, match="orientations"):
        OrientationClass(name, centres, tolerance)


def test_a_goal_is_a_box_and_several_yaw_windows() -> None:
    goal = Goal(-1, 1, -1, 0, 0.0, 0.2, more_yaws=((math.pi, 0.2),), orientations=("side",))
    assert goal.contains((0.0, -0.5, 0.1)) and goal.contains((0.0, -0.5, -math.pi + 0.1))
    assert not goal.contains((0.0, -0.5, math.pi / 2))
    assert goal.yaw_gap(math.pi / 2) == pytest.approx(math.pi / 2 - 0.2)
    assert goal.target == (0.0, 0.0, 0.0)


def test_the_feeder_keeps_the_pegs_classes_and_heavy_end_down() -> None:
    scene = build_feeder(PRESETS["table3"])
    assert scene.orientations == PEG_ORIENTATIONS
    assert scene.goal.orientations == (HEAVY_END_DOWN,)
    assert scene.orientation_names == (HEAVY_END_DOWN, HEAVY_END_UP)


# --- a family's orientations: ------------------------------------------------------------


def test_a_family_names_its_classes_and_its_goal_accepts_one() -> None:
    family = family_from_dict(
        fig1(orientations=CUP_CLASSES, goal=cup_goal(orientation="open end up", yaw_tol=0.35))
    )
    scene = family.build(family.default())
    assert scene.orientation_names == ("open end up", "on its side", "open end down")
    assert scene.goal.orientations == ("open end up",)
    assert (scene.goal.yaw, scene.goal.yaw_tol, scene.goal.more_yaws) == (
        pytest.approx(-math.pi / 2),
        0.35,
        (),
    )
    assert [c.name for c in family.orientations] == list(CUP_CLASSES)
    assert family.orientations[1].centres == (0.0, pytest.approx(math.pi))


def test_a_goal_accepting_a_class_of_two_centres_accepts_both() -> None:
    family = family_from_dict(
        fig1(orientations=CUP_CLASSES, goal=cup_goal(orientation="on its side"))
    )
    goal = family.build(family.default()).goal
    assert goal.windows == ((0.0, QUARTER), (pytest.approx(math.pi), QUARTER))
    assert goal.contains((0.0, -3.0, math.pi - 0.5)) and goal.contains((0.0, -3.0, 0.5))
    assert not goal.contains((0.0, -3.0, -math.pi / 2))


def test_a_goal_may_accept_several_classes() -> None:
    family = family_from_dict(
        fig1(orientations=CUP_CLASSES, goal=cup_goal(orientation=["open end up", "on its side"]))
    )
    goal = family.build(family.default()).goal
    assert goal.orientations == ("open end up", "on its side")
    assert len(goal.windows) == 3


def test_a_family_goal_by_yaw_takes_the_class_that_holds_its_yaw() -> None:
    """fig1's goal (yaw -pi/2): heavy end down with the peg's classes; with the cup's, the
    same goal is open end up."""
    assert load_family(FIG1).build(load_family(FIG1).default()).goal.orientations == (
        HEAVY_END_DOWN,
    )
    family = family_from_dict(fig1(orientations=CUP_CLASSES))
    assert family.build(family.default()).goal.orientations == ("open end up",)


@pytest.mark.parametrize(
    "changes, words",
    [
        (
            {"goal": cup_goal(orientation="open end upp")},
            "goal.orientation = 'open end upp': not an orientation class of the part; the "
            "classes are: open end up, on its side, open end down",
        ),
        ({"goal": cup_goal(orientation="open end up", yaw=0.0)}, "'yaw' or 'orientation'"),
        ({"goal": cup_goal()}, "give 'yaw' and 'yaw_tol', or 'orientation'"),
        ({"goal": cup_goal(orientation=[])}, "goal.orientation: name one or more of"),
        ({"goal": cup_goal(yaw=0.0)}, "goal.yaw_tol is required"),
        (
            {
                "orientations": {"up": {"yaw": "-pi/2", "tolerance": 0.3}},
                "goal": cup_goal(yaw=2.4, yaw_tol=0.1),
            },
            "lies in no orientation class of the part",
        ),
        ({"orientations": {"a": {"tolerance": 1}}}, "orientations.a: give one of 'yaw'"),
        ({"orientations": {"a": {"yaw": 4}}}, "orientations.a.yaw = 4 is outside"),
        ({"orientations": {"a": {"yaw": 0, "tolerance": 0}}}, "orientations.a.tolerance = 0"),
        ({"orientations": {"a": {"yaw": "w"}}}, "orientations.a.yaw = 'w': unknown name"),
        ({"orientations": {OTHER_ORIENTATION: {"yaw": 0}}}, "is the class of a yaw in no"),
        ({"orientations": []}, "orientations: expected a mapping"),
    ],
)
def test_bad_orientations_are_one_line_naming_the_field(changes: dict, words: str) -> None:
    data = fig1(orientations=CUP_CLASSES)
    data.update(copy.deepcopy(changes))
    with pytest.raises(FamilyError) as error:
        family_from_dict(data, prefix="family.")
    message = str(error.value)
    assert "\n" not in message and words in message and "family." in message


# --- face_down: "this face down" ---------------------------------------------------------


def test_a_class_may_be_a_face_down_and_the_cups_faces_give_its_stable_poses() -> None:
    """Reference: feeders.composite_part.stable_poses, which puts each face of the cup's hull
    on a floor by statics. The cup's faces in its part frame (base at x = 0.9, walls at
    y = +-0.5, rims at x = 0), each listed with the cup on its left, give those yaws."""
    from feeders.composite_part import stable_poses

    faces = {
        "open end up": [[0.9, -0.5], [0.9, 0.5]],  # the base's outer face
        "open end down": {"rims": [[[0.0, 0.5], [0.0, 0.15]], [[0.0, -0.15], [0.0, -0.5]]]},
        "on its side": [[[0.0, -0.5], [0.9, -0.5]], [[0.9, 0.5], [0.0, 0.5]]],
    }
    spec = {
        "open end up": {"face_down": faces["open end up"], "tolerance": "pi/4"},
        "open end down": {"face_down": faces["open end down"]["rims"], "tolerance": "pi/4"},
        "on its side": {"face_down": faces["on its side"], "tolerance": "pi/4"},
    }
    family = family_from_dict(fig1(orientations=spec, goal=cup_goal(orientation="open end up")))
    yaws = sorted(c for cls in family.orientations for c in cls.centres)
    expected = sorted(pose.yaw for pose in stable_poses(cup_part()))
    assert len(set(np.round(yaws, 9))) == 4
    assert np.allclose(sorted(set(np.round(yaws, 9))), expected)
    by_name = {c.name: c.centres for c in family.orientations}
    assert by_name["open end up"] == (pytest.approx(-math.pi / 2),)


@pytest.mark.parametrize(
    ("face", "says"),
    [
        ([[0.9, 0.5], [0.9, 0.5]], "the two points are the same"),
        ([[0.9, 0.5]], "expected a face"),
        ("base", "expected a face"),
        ([[0.9, "x"], [0.9, 0.5]], "face_down[0][1]"),
    ],
)
def test_a_bad_face_is_one_line_naming_the_field(face: Any, says: str) -> None:
    spec = {"open end up": {"face_down": face}}
    with pytest.raises(FamilyError, match=r"orientations\.open end up\.face_down") as info:
        family_from_dict(fig1(orientations=spec))
    assert says in str(info.value) and "\n" not in str(info.value)


def test_a_class_gives_a_yaw_or_a_face_not_both() -> None:
    spec = {"up": {"yaw": 0.0, "face_down": [[0.9, -0.5], [0.9, 0.5]]}}
    with pytest.raises(FamilyError, match="give one of 'yaw'"):
        family_from_dict(fig1(orientations=spec))
