"""Physical sanity of scenes read from YAML: each kind of nonsense a user could write (issue 16:
these were accepted and run) is one SceneError naming the field; huge inputs before any
geometry is computed (counted, not timed: issue 22)."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest
import shapely

import feeders.scene_yaml
from feeders.scene_checks import overlap_depth, scene_problems
from feeders.scene_yaml import (
    MAX_TOTAL_VERTICES,
    MAX_VERTICES,
    SceneError,
    environment_from_dict,
    scene_from_dict,
)

BOX: dict[str, Any] = {
    "name": "box",
    "obstacles": [
        {"polygon": [[-6, -4], [6, -4], [6, -3], [-6, -3]]},
        {"polygon": [[-6, 3], [6, 3], [6, 4], [-6, 4]]},
    ],
    "part": {"length": 1.0, "width": 0.5, "mass": 1.0, "heavy_fraction": 0.5},
    "bounds": [-5, 5, -2.5, 2.5],
    "starts": {"drop": [0.0, 2.0, 0.0]},
    "goal": {"x": [-1, 1], "y": [-2.5, -2], "yaw": 0.0, "yaw_tol": 0.5},
}


def _with(path: str, value: Any) -> dict[str, Any]:
    """BOX with the field at ``path`` (dots and list indices) replaced by ``value``."""
    doc = copy.deepcopy(BOX)
    *head, last = path.split(".")
    node: Any = doc
    for key in head:
        node = node[int(key)] if isinstance(node, list) else node[key]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value
    return doc


def test_the_sane_scene_has_no_problems() -> None:
    assert scene_problems(scene_from_dict(BOX)) == []


@pytest.mark.parametrize(
    ("path", "value", "names"),
    [
        ("gravity", [0.0, -1e308], "gravity"),
        ("bounds", [-1e308, 1e308, -5, 5], "bounds"),
        ("starts", {"drop": [0.0, 3.5, 0.0]}, "starts.drop"),  # inside the roof
        ("starts", {"drop": [9.0, 0.0, 0.0]}, "starts.drop"),  # outside the bounds
        ("starts", {"drop": [0.0, 0.0, 1e308]}, "starts.drop"),  # yaw
        ("goal.x", [20, 30], "goal"),  # outside the bounds
        ("goal.y", [-2.5, 2.5], None),  # a sane, larger goal: no error (control case)
        # longer than the bounds' diagonal (10 x 5: 11.2)
        ("part", {"length": 100, "width": 50, "mass": 1, "heavy_fraction": 0.5}, "part.length"),
        # fits, but not where it starts
        ("part", {"length": 10, "width": 5, "mass": 1, "heavy_fraction": 0.5}, "starts.drop"),
    ],
)
def test_nonsense_is_refused_with_the_field_named(path: str, value: Any, names: str | None):
    doc = _with(path, value)
    if names is None:
        scene_from_dict(doc)
        return
    with pytest.raises(SceneError) as info:
        scene_from_dict(doc)
    assert names in str(info.value) and "\n" not in str(info.value)


def test_a_goal_inside_an_obstacle_is_unreachable() -> None:
    doc = _with("goal", {"x": [-1, 1], "y": [3.2, 3.8], "yaw": 0.0, "yaw_tol": 0.5})
    doc["bounds"] = [-5, 5, -2.5, 3.9]
    with pytest.raises(SceneError, match="goal: the box lies inside the obstacles"):
        scene_from_dict(doc)


@pytest.mark.parametrize(
    ("radius", "names"), [(1e6, "obstacles: coordinates"), (1e5, "goal"), (1.0, "starts.drop")]
)
def test_a_circle_over_the_start_is_refused(radius: float, names: str) -> None:
    """A disc of radius 1e6 reaches past the largest coordinate allowed; one of 1e5 swallows
    the start and the goal (the goal is named first); one of radius 1 only the start."""
    doc = copy.deepcopy(BOX)
    doc["obstacles"].append({"circle": {"centre": [0, 2], "radius": radius}})
    with pytest.raises(SceneError, match=names):
        scene_from_dict(doc)


@pytest.mark.parametrize(
    ("change", "names"),
    [
        (lambda d: d["obstacles"].append({"polygon": _star(100_000)}), "obstacles[2].polygon"),
        (lambda d: d.update(starts={f"s{i}": [0, 0, 0] for i in range(10_000)}), "starts"),
        (
            lambda d: d.update(obstacles=[{"circle": {"centre": [0, -9], "radius": 1}}] * 2000),
            "obs",
        ),
    ],
)
def test_huge_inputs_are_refused_before_any_geometry(change, names: str, geometry) -> None:
    """A polygon of 10^5 points and a scene of 10^4 starts used to hang (ear clipping is
    cubic): the counts are checked before any geometry."""
    doc = copy.deepcopy(BOX)
    change(doc)
    with pytest.raises(SceneError) as info:
        scene_from_dict(doc)
    assert names in str(info.value)
    assert geometry == []


@pytest.fixture
def geometry(monkeypatch) -> list[str]:
    """The geometry a scene reader computes (ear clipping of each polygon, the physical checks
    of the whole scene), recorded as it is asked for: a clock-free measure of "at once"."""
    calls: list[str] = []
    clip, check = feeders.scene_yaml.convex_pieces, feeders.scene_yaml.scene_problems

    def clipping(*args, **kwargs):
        calls.append("convex_pieces")
        return clip(*args, **kwargs)

    def checking(*args, **kwargs):
        calls.append("scene_problems")
        return check(*args, **kwargs)

    monkeypatch.setattr(feeders.scene_yaml, "convex_pieces", clipping)
    monkeypatch.setattr(feeders.scene_yaml, "scene_problems", checking)
    return calls


def test_the_geometry_probe_sees_a_sound_scene_clipped_and_checked(geometry) -> None:
    """The probe the refusals below rely on does see the geometry of a scene that is read."""
    scene_from_dict(copy.deepcopy(BOX))
    assert geometry == ["convex_pieces", "convex_pieces", "scene_problems"]


def _star(n: int) -> list[list[float]]:
    angles = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    radius = np.where(np.arange(n) % 2 == 0, 1.0, 0.5)
    return np.column_stack([radius * np.cos(angles), radius * np.sin(angles) - 10]).tolist()


def test_run_config_gravity_is_checked_by_the_same_rule() -> None:
    with pytest.raises(SceneError, match=r"feeder\.gravity = .* at most 1000"):
        environment_from_dict({"gravity": [0.0, 1e308]}, prefix="feeder.")


def test_overlap_depth_of_a_square_sunk_into_a_floor() -> None:
    """Hand-worked: a unit square whose bottom is 0.1 below the floor's surface y = 0."""
    floor = shapely.box(-5.0, -1.0, 5.0, 0.0)
    square = np.array([[0.0, -0.1], [1.0, -0.1], [1.0, 0.9], [0.0, 0.9]])
    assert overlap_depth(floor, square) == pytest.approx(0.1)
    assert overlap_depth(floor, square + np.array([0.0, 0.2])) == 0.0


def test_many_star_polygons_within_the_per_polygon_limit_are_refused_by_the_total(
    geometry,
) -> None:
    """20 stars of 200 points each clipped in ~5 s (ear clipping is cubic): the total count
    is checked before any geometry."""
    doc = copy.deepcopy(BOX)
    star = _star(MAX_VERTICES)
    doc["obstacles"] += [{"polygon": [[x + 3 * k, y] for x, y in star]} for k in range(20)]
    with pytest.raises(SceneError, match=rf"at most {MAX_TOTAL_VERTICES} are allowed"):
        scene_from_dict(doc)
    assert geometry == []


@pytest.mark.parametrize("name", ["../../etc/x", "x" * 5000, "", "a\nb", [1, 2]])
def test_a_scene_name_that_cannot_name_a_file_is_refused(name) -> None:
    with pytest.raises(SceneError, match=r"^name"):
        scene_from_dict(_with("name", name))


def test_a_cups_start_is_checked_piece_by_piece() -> None:
    """The cup (issue 24) straddling a thin post with its opening is a sound start, though
    the post lies inside its convex hull; moved onto the post with a wall, it overlaps by
    the post's half width (0.05) and is refused."""
    import dataclasses

    from feeders.cup import cup_part

    post = {"polygon": [[-0.05, -3], [0.05, -3], [0.05, 0.3], [-0.05, 0.3]]}
    doc = copy.deepcopy(BOX)
    doc["obstacles"].append(post)
    del doc["part"]
    scene = dataclasses.replace(scene_from_dict(doc), part=cup_part())
    hooked = dataclasses.replace(scene, starts={"drop": (0.0, 0.6, -np.pi / 2 + np.pi)})
    assert scene_problems(hooked) == []
    walled = dataclasses.replace(scene, starts={"drop": (0.425, 0.6, np.pi / 2)})
    (problem,) = scene_problems(walled)
    assert "starts.drop" in problem and "0.05" in problem
