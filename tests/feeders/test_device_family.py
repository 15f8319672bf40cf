"""Specification of feeders.device_family and of the shipped family feeders/families/fig1.yaml.

References: shapely as an independent geometry implementation (validity and convexity of the
built pieces, their overlap with the part's start poses), the geometric level's own validity
test at the start poses, the fig1 file's formulas worked out by hand with math, and Halton
points of the family's box (feeders.halton).
"""

from __future__ import annotations

import copy
import math
import pickle
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import shapely
import yaml

from feeders.device_family import DeviceFamily, FamilyError, family_from_dict, load_family
from feeders.feeder import DegenerateDesign
from feeders.halton import halton_points
from feeders.scene import Scene
from validity.geometric import GeometricLevel

FIG1 = Path(__file__).resolve().parents[2] / "feeders" / "families" / "fig1.yaml"

SQUARE_CUP: dict[str, Any] = {
    "name": "cup",
    "parameters": {
        "w": {"low": 2.0, "high": 4.0, "default": 3.0},
        "h": {"low": 0.5, "high": 2.0, "default": 1.0},
    },
    "pieces": [
        {"label": "floor", "polygon": [["-w", -1], ["w", -1], ["w", 0], ["-w", 0]]},
        {"polygon": [["-w - 1", 0], ["-w", 0], ["-w", "h + 3"], ["-w - 1", "h + 3"]]},
        {"polygon": [["w", 0], ["w + 1", 0], ["w + 1", "h + 3"], ["w", "h + 3"]]},
        {"label": "pin", "disc": {"centre": [0, "h + 2"], "radius": "h / 4"}},
    ],
    "entries": {"drop": [0, "h + 4.5", 0]},
    "goal": {"x": ["-w + 1.2", "w - 1.2"], "y": [0.3, 1.0], "yaw": 0, "yaw_tol": 0.3},
    "rules": [{"require": "w > 2 * h", "reason": "the cup is too narrow for its pin"}],
    "bounds": ["-w", "w", 0, "h + 6"],
}


def cup(**changes: Any) -> dict[str, Any]:
    data = copy.deepcopy(SQUARE_CUP)
    data.update(changes)
    return data


@pytest.fixture(scope="module")
def fig1() -> DeviceFamily:
    return load_family(FIG1)


def _pieces_are_valid_convex_polygons(scene: Scene) -> None:
    for vertices, label in zip(scene.obstacles.polygons, scene.obstacles.labels, strict=False):
        polygon = shapely.Polygon(vertices)
        assert polygon.is_valid, label
        assert polygon.area > 0, label
        assert polygon.convex_hull.area == pytest.approx(polygon.area, rel=1e-12), label
        assert shapely.LinearRing(vertices).is_ccw, label


def _starts_are_clear(scene: Scene) -> None:
    level = GeometricLevel(scene)
    solid = shapely.union_all(
        [shapely.Polygon(p) for p in scene.obstacles.polygons]
        + [shapely.Point(c[:2]).buffer(c[2]) for c in scene.obstacles.circles]
    )
    for name, (x, y, yaw) in scene.starts.items():
        assert level.is_valid((x, y, yaw)), name
        c, s = math.cos(yaw), math.sin(yaw)
        corners = scene.part.body_vertices() @ np.array([[c, s], [-s, c]]) + np.array([x, y])
        assert shapely.Polygon(corners).distance(solid) > 0.01, name


# --- the fig1 family --------------------------------------------------------------------


def test_fig1_reads_its_six_parameters_in_order(fig1: DeviceFamily) -> None:
    assert fig1.name == "fig1"
    assert fig1.vector_names == ("theta", "chute_width", "exit_width", "pin_x", "pin_y", "pin_r")
    low, high = fig1.bounds()
    assert np.all(low < high)
    assert np.all((low <= fig1.default()) & (fig1.default() <= high))
    assert [e[0] for e in fig1.entries] == ["open_leading", "open_trailing"]


def test_fig1_default_builds_a_scene_with_valid_pieces_and_clear_starts(
    fig1: DeviceFamily,
) -> None:
    scene = fig1.build(fig1.default())
    assert isinstance(scene, Scene)
    assert len(scene.obstacles.polygons) == 11
    assert scene.obstacles.circles.tolist() == [[-0.6, 1.4, 0.25]]
    assert scene.obstacles.labels[-1] == "pin B"
    _pieces_are_valid_convex_polygons(scene)
    _starts_are_clear(scene)


def test_fig1_formulas_by_hand(fig1: DeviceFamily) -> None:
    """Pose, goal and bounds from the file's formulas, worked out with math at the default."""
    scene = fig1.build(fig1.default())
    theta, a, b = 0.5, 1.2, 1.2
    along, across = (
        np.array([math.cos(theta), math.sin(theta)]),
        np.array([-math.sin(theta), math.cos(theta)]),
    )
    lip = np.array([1.0, 2.2])
    leading = lip + 3.29 * along + a / 2 * across
    assert scene.starts["open_leading"] == pytest.approx((*leading, theta), abs=1e-12)
    assert scene.starts["open_trailing"][2] == pytest.approx(theta - math.pi, abs=1e-12)
    # the two entries place the same part: their middles coincide (centre of mass 0.44 off it)
    middles = [
        np.array(scene.starts[o][:2]) - 0.44 * np.array([math.cos(y), math.sin(y)])
        for o, y in (("open_leading", theta), ("open_trailing", theta - math.pi))
    ]
    assert middles[0] == pytest.approx(middles[1], abs=1e-9)
    assert scene.goal.x_min == -b / 2 and scene.goal.x_max == b / 2
    assert scene.goal.yaw == pytest.approx(-math.pi / 2)
    assert scene.bounds == pytest.approx(
        (-2.5, 1.0 + 4 * math.cos(theta), -4.4, 2.2 + 4 * math.sin(theta) + a * math.cos(theta))
    )


def test_fig1_pin_follows_its_parameters(fig1: DeviceFamily) -> None:
    values = dict(zip(fig1.vector_names, fig1.default().tolist(), strict=True))
    values.update(pin_x=-1.0, pin_y=2.0, pin_r=0.3)
    scene = fig1.build(values)
    assert scene.obstacles.circles.tolist() == [[-1.0, 2.0, 0.3]]


def test_fig1_halton_points_build_or_fail_a_rule_with_its_reason(fig1: DeviceFamily) -> None:
    reasons = {rule.reason for rule in fig1.rules}
    built, refused = 0, set()
    for row in halton_points(64, 7, fig1.space()):
        try:
            scene = fig1.build(row)
        except DegenerateDesign as exc:
            assert exc.reason in reasons, exc.reason
            refused.add(exc.reason)
            continue
        built += 1
        _pieces_are_valid_convex_polygons(scene)
        _starts_are_clear(scene)
    assert built >= 32  # most of the box can be built
    assert refused  # and the rules stop some of it


def test_fig1_rules_stop_a_build_with_their_reason(fig1: DeviceFamily) -> None:
    values = dict(zip(fig1.vector_names, fig1.default().tolist(), strict=True))
    values.update(pin_x=0.6, pin_r=0.4)  # reaches past x = 1.0, the wall below the lip
    with pytest.raises(DegenerateDesign) as error:
        fig1.build(values)
    assert error.value.reason == "pin B touches the cavity's left wall or the wall below the lip"
    assert error.value.parameters == ("pin_x", "pin_r")


# --- building -----------------------------------------------------------------------------


def test_a_vector_and_a_mapping_build_the_same_scene() -> None:
    family = family_from_dict(cup())
    by_vector = family.build([3.5, 1.5])
    by_mapping = family.build({"h": 1.5, "w": 3.5})
    assert by_vector.obstacles.polygons[0].tolist() == by_mapping.obstacles.polygons[0].tolist()
    assert by_vector.starts == {"drop": (0.0, 6.0, 0.0)}
    assert by_vector.bounds == (-3.5, 3.5, 0.0, 7.5)
    assert by_vector.obstacles.circles.tolist() == [[0.0, 3.5, 0.375]]


def test_a_clockwise_polygon_is_turned_counter_clockwise() -> None:
    data = cup()
    data["pieces"][0]["polygon"] = data["pieces"][0]["polygon"][::-1]
    scene = family_from_dict(data).build([3.0, 1.0])
    assert shapely.LinearRing(scene.obstacles.polygons[0]).is_ccw


def test_wrong_vectors_are_refused_naming_the_parameters() -> None:
    family = family_from_dict(cup())
    with pytest.raises(ValueError, match="1 values for 2 parameters"):
        family.build([3.0])
    with pytest.raises(ValueError, match="missing"):
        family.build({"w": 3.0})
    with pytest.raises(ValueError, match="parameter h = nan is not finite"):
        family.build([3.0, math.nan])


def test_a_failing_rule_stops_the_build_with_its_reason() -> None:
    family = family_from_dict(cup())
    with pytest.raises(DegenerateDesign) as error:
        family.build({"w": 2.0, "h": 1.5})
    assert error.value.reason == "the cup is too narrow for its pin"
    assert error.value.parameters == ("w", "h")


@pytest.mark.parametrize(
    ("polygon", "words"),
    [
        ([[0, 0], [2, 0], ["h - 1", 1], ["2 - h", 1]], "crosses itself"),  # h = 2: convex
        ([[0, 0], [2, 0], [1, "h - 1"]], "zero area"),  # h = 1: the apex on the base
        ([[0, 0], [2, 0], [2, 2], [1, "h"], [0, 2]], "not convex"),
    ],
)
def test_degenerate_pieces_stop_the_build(polygon: list, words: str) -> None:
    data = cup(rules=[])
    data["pieces"].append({"label": "bad piece", "polygon": polygon})
    data["parameters"]["h"]["default"] = 2.0  # the default builds: a convex piece
    family = family_from_dict(data)
    with pytest.raises(DegenerateDesign, match=f"bad piece: the polygon .*{words}"):
        family.build({"w": 3.0, "h": 1.0})


def test_an_expression_error_at_a_vector_is_a_degenerate_design() -> None:
    data = cup()
    data["entries"]["drop"] = [0, "h + 4.5", "0.1 / (w - 3.5)"]
    family = family_from_dict(data)
    with pytest.raises(DegenerateDesign) as error:
        family.build({"w": 3.5, "h": 1.0})
    assert "entries.drop[2]" in error.value.reason
    assert "division by zero" in error.value.reason


def test_a_start_inside_the_pieces_stops_the_build() -> None:
    data = cup()
    data["entries"]["drop"] = [0, "h + 4.5 - 12 * (h - 1)", 0]  # onto the pin for h = 1.2
    family = family_from_dict(data)
    with pytest.raises(DegenerateDesign, match=r"starts\.drop: the part there overlaps"):
        family.build({"w": 3.0, "h": 1.2})


def test_without_bounds_the_pieces_box_is_used() -> None:
    data = cup(entries={"drop": [0, 1.2, 0]})
    del data["bounds"]
    scene = family_from_dict(data).build([3.0, 1.0])
    assert scene.bounds == (-4.0, 4.0, -1.0, 4.0)


def test_the_environment_is_read_as_in_a_scene_file() -> None:
    family = family_from_dict(
        cup(part={"length": 1.0, "width": 0.4}, friction=0.2, inputs={"max_force": 1.0})
    )
    scene = family.build(family.default())
    assert (scene.part.length, scene.part.width, scene.friction) == (1.0, 0.4, 0.2)
    assert scene.inputs.max_force == 1.0


def test_a_family_is_plain_data() -> None:
    family = family_from_dict(cup())
    assert pickle.loads(pickle.dumps(family)) == family
    assert family_from_dict(cup()) == family


def test_its_box_is_sampled_by_halton() -> None:
    family = family_from_dict(cup())
    points = halton_points(16, 3, family.space())
    assert points.shape == (16, 2)
    low, high = family.bounds()
    assert np.all((points >= low) & (points <= high))


def test_a_pin_is_a_circle_as_in_a_scene_file_and_disc_is_the_same() -> None:
    """One vocabulary with scene files (``circle: {centre, radius}``); ``disc:``, which
    fig1.yaml uses, is read the same way."""
    written = copy.deepcopy(SQUARE_CUP["pieces"])
    written[3] = {"label": "pin", "circle": written[3]["disc"]}
    by_circle = family_from_dict(cup(pieces=written)).build([3.0, 1.0])
    by_disc = family_from_dict(cup()).build([3.0, 1.0])
    assert np.array_equal(by_circle.obstacles.circles, by_disc.obstacles.circles)
    assert by_circle.obstacles.circles.tolist() == [[0.0, 3.0, 0.25]]
    assert by_circle.obstacles.labels == by_disc.obstacles.labels


# --- refused at load ----------------------------------------------------------------------


def test_a_family_whose_default_cannot_be_built_is_refused_at_load() -> None:
    data = cup()
    data["parameters"]["h"]["default"] = 1.6  # w = 3 < 2 h
    with pytest.raises(FamilyError) as error:
        family_from_dict(data, prefix="family.")
    message = str(error.value)
    assert message.startswith("family.parameters: the defaults (w = 3, h = 1.6) cannot be built")
    assert "the cup is too narrow for its pin" in message


@pytest.mark.parametrize(
    ("change", "words"),
    [
        ({"pieces": [{"disc": {"centre": [0, 1], "radius": "h + q"}}]}, "pieces[0].disc.radius"),
        ({"entries": {"drop": [0, "1 / (w - w)", 0]}}, "division by zero"),
        ({"rules": [{"require": "w + 1", "reason": "x"}]}, "rules[0].require"),
        ({"rules": [{"require": "w > 1"}]}, "rules[0]: needs 'require'"),
        ({"goal": {"x": [0, 1], "y": [0, 1], "yaw": "w.real", "yaw_tol": 0.3}}, "goal.yaw"),
        ({"goal": {"x": [0, 1], "y": [0, 1], "yaw": 0}}, "goal.yaw_tol is required"),
        ({"bounds": [0, 1, 2]}, "bounds: expected [x_min"),
        ({"parameters": {"pi": {"low": 0, "high": 1, "default": 0}}}, "parameters.pi"),
        ({"parameters": {"sin": {"low": 0, "high": 1, "default": 0}}}, "parameters.sin"),
        ({"parameters": {"w": {"low": 2, "high": 1, "default": 1}}}, "need low < high"),
        ({"parameters": {"w": {"low": 0, "high": 1, "default": 2}}}, "parameters.w.default"),
        ({"parameters": {"w": {"low": 0, "high": 1}}}, "parameters.w.default is required"),
        ({"pieces": [{"polygon": [[0, 0], [1, 0]]}]}, "pieces[0].polygon: expected a list"),
        (
            {"pieces": [{"circle": {"centre": [0, 0], "radius": 1}, "disc": {}}]},
            "pieces[0]: give exactly one of 'polygon' or 'circle'",
        ),
        ({"pieces": [{"circle": {"centre": [0, 1], "radius": "q"}}]}, "pieces[0].circle.radius"),
        ({"pieces": [{"circle": {"centre": [0, 1]}}]}, "pieces[0].circle: needs 'centre'"),
        ({"pieces": [{"sphere": {"centre": [0, 0], "radius": 1}}]}, "unknown key"),
        ({"pieces": []}, "pieces: expected a non-empty list"),
        ({"colour": "red"}, "unknown key"),
        ({"friction": 20}, "friction"),
    ],
)
def test_bad_families_are_refused_in_one_line_naming_the_field(change: dict, words: str) -> None:
    with pytest.raises(FamilyError) as error:
        family_from_dict(cup(**change), prefix="family.")
    message = str(error.value)
    assert words in message
    assert "\n" not in message


def test_a_file_error_names_the_file(tmp_path: Path) -> None:
    data = cup(entries={"drop": [0, "h + zeta", 0]})
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    with pytest.raises(FamilyError) as error:
        load_family(path)
    message = str(error.value)
    assert message.startswith(f"{path}: entries.drop[1]")
    assert "unknown name 'zeta'" in message
    assert "the parameters are: w, h" in message
