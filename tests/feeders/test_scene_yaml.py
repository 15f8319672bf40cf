"""Specification of feeders.scene_yaml and of the example scenes in experiments/scenes/.

References: build_feeder for the parametric scenes (the YAML layer must not change the
device), shapely as an independent geometry implementation for the convex decomposition of
free-form polygons and for the example scenes' contacts, the paper's Table 3 and Fig. 4 values
typed in, and trigonometry for the 30-degree incline.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
import yaml
from shapely.geometry import Point, Polygon

from feeders.design import PRESETS
from feeders.feeder import DEFAULT_FRICTION, build_feeder
from feeders.part import Peg
from feeders.scene import Scene
from feeders.scene_yaml import SceneError, load_scene, scene_from_dict

SCENES = Path(__file__).resolve().parents[2] / "experiments" / "scenes"
EXAMPLES = ["table3.yaml", "custom_design.yaml", "incline.yaml", "drop.yaml"]

FREE_FORM = {
    "name": "cup",
    "obstacles": [
        {"polygon": [[-3, 0], [3, 0], [3, 3], [2, 3], [2, 1], [-2, 1], [-2, 3], [-3, 3]]},
        {"circle": {"centre": [0, 5], "radius": 0.5}, "label": "pin"},
    ],
    "bounds": [-5, 5, 0, 8],
    "starts": {"drop": [0.0, 7.0, 0.0]},
    "goal": {"x": [-1, 1], "y": [1, 2], "yaw": 0.0, "yaw_tol": 0.3},
}


def _part_polygon(part: Peg, pose) -> Polygon:
    x, y, yaw = pose
    turned = shapely.affinity.rotate(
        Polygon(part.body_vertices()), yaw, origin=(0.0, 0.0), use_radians=True
    )
    return shapely.affinity.translate(turned, x, y)


def _assert_same_scene(loaded: Scene, built: Scene) -> None:
    assert loaded.design == built.design
    assert loaded.part == built.part
    assert (loaded.friction, loaded.gravity, loaded.inputs) == (
        built.friction,
        built.gravity,
        built.inputs,
    )
    assert loaded.obstacles.labels == built.obstacles.labels
    assert len(loaded.obstacles.polygons) == len(built.obstacles.polygons)
    for a, b in zip(loaded.obstacles.polygons, built.obstacles.polygons, strict=True):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(loaded.obstacles.circles, built.obstacles.circles)
    np.testing.assert_array_equal(loaded.outline, built.outline)
    assert loaded.starts == built.starts
    assert loaded.goal == built.goal
    assert loaded.bounds == built.bounds


def _write(tmp_path: Path, data, name: str = "scene.yaml") -> Path:
    path = tmp_path / name
    path.write_text(data if isinstance(data, str) else yaml.safe_dump(data))
    return path


def _scene_error(path: Path) -> str:
    with pytest.raises(SceneError) as info:
        load_scene(path)
    message = str(info.value)
    assert "\n" not in message, f"message is not one line: {message!r}"
    return message


# --- example scenes -------------------------------------------------------------------------


@pytest.mark.parametrize("name", EXAMPLES)
def test_example_scene_loads_and_says_what_it_is_for(name):
    path = SCENES / name
    first_line = path.read_text().splitlines()[0]
    assert first_line.startswith("# ") and len(first_line) > 20  # a comment header
    scene = load_scene(path)
    assert isinstance(scene, Scene)
    assert scene.name == path.stem
    assert scene.starts


def test_table3_scene_is_the_table3_feeder():
    """Reference: build_feeder of the paper's Table 3 design (values typed in) with the default
    part and friction (the file spells out mu = 0.05, the calibrated default)."""
    scene = load_scene(SCENES / "table3.yaml")
    assert scene.design.to_dict() == {
        "a": 1.1, "b": 1.1086, "c": 0.7979, "d": 3.0078, "e": -1.9, "fx": -0.9849,
        "fy": 1.0098, "gx": 0.733, "gy": 2.0388, "r": 0.101, "theta": 0.4673, "alpha": 1.0472,
    }  # fmt: skip
    assert scene.friction == 0.05 == DEFAULT_FRICTION
    _assert_same_scene(scene, build_feeder(PRESETS["table3"], name="table3"))


def test_custom_design_scene_is_the_fig4_feeder():
    """Reference: build_feeder of the Fig. 4 preset; the file gives its 12 values with f and g
    as pairs."""
    text = (SCENES / "custom_design.yaml").read_text()
    design = yaml.safe_load(text)["feeder"]["design"]
    assert design["f"] == [-0.616, 1.929] and design["g"] == [1.325, 2.666]
    assert len(design) == 10  # a, b, c, d, e, f, g, r, theta, alpha: 12 values
    scene = load_scene(SCENES / "custom_design.yaml")
    _assert_same_scene(scene, build_feeder(PRESETS["fig4"], name="custom_design"))


def test_preset_and_explicit_design_give_the_same_geometry(tmp_path):
    """A preset name and the same 12 values written out build the same device."""
    values = PRESETS["fig8b"].to_dict()
    explicit = {k: v for k, v in values.items() if k not in ("fx", "fy", "gx", "gy")}
    explicit["f"] = [values["fx"], values["fy"]]
    explicit["g"] = [values["gx"], values["gy"]]
    by_preset = load_scene(_write(tmp_path, {"feeder": {"preset": "fig8b"}}, "a.yaml"))
    by_values = load_scene(_write(tmp_path, {"feeder": {"design": explicit}}, "b.yaml"))
    _assert_same_scene(by_preset, by_values)
    _assert_same_scene(by_preset, build_feeder(PRESETS["fig8b"]))


def test_feeder_scene_passes_part_gravity_and_inputs_through(tmp_path):
    data = {
        "feeder": {"preset": "fig9"},
        "part": {"length": 2.2, "width": 0.9, "mass": 2.0, "heavy_fraction": 0.8},
        "friction": 0.5,
        "gravity": [0.0, -1.62],
        "inputs": {"max_speed": 2.0, "max_turn": 0.5},
    }
    scene = load_scene(_write(tmp_path, data))
    part = Peg.two_density(length=2.2, width=0.9, mass=2.0, heavy_fraction=0.8)
    assert scene.part == part
    assert (scene.friction, scene.gravity) == (0.5, (0.0, -1.62))
    assert (scene.inputs.max_speed, scene.inputs.max_turn) == (2.0, 0.5)
    _assert_same_scene(scene, build_feeder(PRESETS["fig9"], part, scene.inputs, 0.5, (0.0, -1.62)))


def test_incline_scene_is_a_box_resting_on_a_30_degree_incline():
    """Reference: trigonometry of the 30-degree incline and shapely contacts. The box is uniform
    (2 x 1, centre of mass in the middle), rests on the incline (touching, not overlapping), its
    long side along the slope, and the goal lies further down the same slope."""
    scene = load_scene(SCENES / "incline.yaml")
    assert scene.friction == 0.3 and scene.gravity == (0.0, -9.81)
    part = scene.part
    assert (part.length, part.width, part.com_offset) == (2.0, 1.0, 0.0)
    assert scene.obstacles.labels == ("incline",)
    (wedge,) = scene.obstacles.polygons
    incline = Polygon(wedge)
    xs, ys = np.array(wedge)[:, 0], np.array(wedge)[:, 1]
    run, rise = xs.max() - xs.min(), ys.max() - ys.min()
    assert math.degrees(math.atan2(rise, run)) == pytest.approx(30.0, abs=1e-9)
    assert math.hypot(run, rise) == pytest.approx(20.0, abs=1e-9)  # a long incline
    assert scene.friction < math.tan(math.radians(30))  # so the box slides
    (start,) = scene.starts.values()
    assert start[2] == pytest.approx(-math.pi / 6, abs=1e-12)
    box = _part_polygon(part, start)
    assert box.intersection(incline).area < 1e-9
    assert box.distance(incline) < 1e-9
    goal = scene.goal
    assert goal.yaw == pytest.approx(-math.pi / 6, abs=1e-12)
    # the resting box's centre line: start + s (cos 30, -sin 30); some of it is in the goal
    down = np.array([math.cos(math.pi / 6), -math.sin(math.pi / 6)])
    on_line = [(s, (*(start[:2] + s * down), start[2])) for s in np.linspace(0, 20, 2001)]
    along = [s for s, pose in on_line if goal.contains(pose)]
    assert along and min(along) > 5.0
    pose = (*(start[:2] + along[len(along) // 2] * down), start[2])
    assert _part_polygon(part, pose).intersection(incline).area < 1e-9
    for pose in (start, goal.target):
        assert scene.bounds[0] <= pose[0] <= scene.bounds[1]
        assert scene.bounds[2] <= pose[1] <= scene.bounds[3]


def test_drop_scene_is_a_peg_above_a_pin_and_a_floor():
    """Reference: shapely. The start is clear of everything and above the pin, the pin above
    the floor, and a peg lying flat on the floor is in the goal."""
    scene = load_scene(SCENES / "drop.yaml")
    (floor,) = (Polygon(p) for p in scene.obstacles.polygons)
    ((cx, cy, r),) = scene.obstacles.circles
    pin = Point(cx, cy).buffer(r, quad_segs=64)
    (start,) = scene.starts.values()
    peg = _part_polygon(scene.part, start)
    assert peg.distance(pin) > 0 and peg.distance(floor) > 0
    assert peg.bounds[1] > cy + r > cy - r > floor.bounds[3]
    assert peg.bounds[0] < cx < peg.bounds[2]  # falls onto the pin
    lying = (start[0], floor.bounds[3] + scene.part.width / 2, 0.0)
    assert _part_polygon(scene.part, lying).intersection(floor).area < 1e-9
    assert scene.goal.contains(lying)
    assert scene.goal.contains((lying[0], lying[1], math.pi))
    assert not scene.goal.contains(start)


# --- free-form polygons ---------------------------------------------------------------------


@pytest.mark.parametrize(
    "polygon",
    [
        # a cup (U shape), counter-clockwise
        [[-3, 0], [3, 0], [3, 3], [2, 3], [2, 1], [-2, 1], [-2, 3], [-3, 3]],
        # an L shape, clockwise
        [[0, 0], [0, 4], [1, 4], [1, 1], [4, 1], [4, 0]],
        # an arrow with reflex corners on both sides
        [[0, 0], [4, 2], [0, 4], [1, 2]],
        # a comb: many reflex corners
        [[0, 0], [7, 0], [7, 3], [6, 3], [6, 1], [5, 1], [5, 3], [4, 3], [4, 1], [3, 1],
         [3, 3], [2, 3], [2, 1], [1, 1], [1, 3], [0, 3]],
        # a convex polygon stays one piece
        [[0, 0], [2, 0], [3, 1], [1, 2]],
    ],
)  # fmt: skip
def test_free_form_polygon_becomes_convex_pieces_whose_union_is_the_polygon(polygon):
    """Reference: shapely (union, areas, convex hulls, orientation)."""
    data = copy.deepcopy(FREE_FORM)
    data["obstacles"][0] = {"polygon": polygon, "label": "cup"}
    scene = scene_from_dict(data)
    pieces = [Polygon(p) for p in scene.obstacles.polygons]
    target = Polygon(polygon)
    assert target.is_valid
    for piece in pieces:
        assert piece.is_valid and piece.exterior.is_ccw
        assert piece.area > 0
        assert piece.convex_hull.area == pytest.approx(piece.area, rel=1e-12)
    union = shapely.unary_union(pieces)
    assert union.symmetric_difference(target).area < 1e-9
    assert sum(p.area for p in pieces) == pytest.approx(target.area, rel=1e-12)  # no overlap
    assert (len(pieces) == 1) == (target.convex_hull.area == target.area)
    assert scene.obstacles.labels == ("cup",) * len(pieces) + ("pin",)


def test_free_form_scene_fields():
    scene = scene_from_dict(FREE_FORM)
    assert scene.name == "cup"
    assert scene.design is None and scene.outline is None
    assert scene.bounds == (-5.0, 5.0, 0.0, 8.0)
    assert scene.starts == {"drop": (0.0, 7.0, 0.0)}
    np.testing.assert_array_equal(scene.obstacles.circles, [[0.0, 5.0, 0.5]])
    goal = scene.goal
    assert (goal.x_min, goal.x_max, goal.y_min, goal.y_max) == (-1.0, 1.0, 1.0, 2.0)
    assert (goal.yaw, goal.yaw_tol) == (0.0, 0.3)
    assert scene.friction == DEFAULT_FRICTION and scene.gravity == (0.0, -9.81)  # defaults
    assert scene.part == Peg.two_density()


# --- errors ---------------------------------------------------------------------------------


def _with(**changes):
    data = copy.deepcopy(FREE_FORM)
    for key, value in changes.items():
        if value is None:
            del data[key]
        else:
            data[key] = value
    return data


def test_bad_friction_names_the_field_and_range(tmp_path):
    message = _scene_error(_write(tmp_path, _with(friction=-0.1)))
    assert "friction" in message and "[0, 10]" in message
    message = _scene_error(_write(tmp_path, _with(friction="slippery")))
    assert "friction" in message


def test_negative_radius_names_the_field_and_range(tmp_path):
    data = _with()
    data["obstacles"][1]["circle"]["radius"] = -0.5
    message = _scene_error(_write(tmp_path, data))
    assert "obstacles[1].circle.radius" in message and "[1e-09, 1e+06]" in message


def test_unknown_key_is_named(tmp_path):
    message = _scene_error(_write(tmp_path, _with(frictoin=0.3)))
    assert "frictoin" in message and "unknown" in message
    data = _with()
    data["goal"]["z"] = [0, 1]
    message = _scene_error(_write(tmp_path, data))
    assert "goal" in message and "'z'" in message


def test_missing_goal_is_named(tmp_path):
    message = _scene_error(_write(tmp_path, _with(goal=None)))
    assert "goal" in message and "required" in message
    data = _with()
    del data["goal"]["yaw_tol"]
    assert "goal.yaw_tol" in _scene_error(_write(tmp_path, data))


def test_feeder_and_obstacles_together_are_refused(tmp_path):
    message = _scene_error(_write(tmp_path, _with(feeder={"preset": "table3"})))
    assert "feeder" in message and "obstacles" in message


def test_neither_feeder_nor_obstacles_is_refused(tmp_path):
    message = _scene_error(_write(tmp_path, _with(obstacles=None)))
    assert "feeder" in message and "obstacles" in message


def test_unreadable_file_names_the_file(tmp_path):
    missing = tmp_path / "no_such_scene.yaml"
    assert "no_such_scene.yaml" in _scene_error(missing)
    assert str(tmp_path) in _scene_error(tmp_path)  # a directory is not a scene file


def test_malformed_yaml_is_a_one_line_scene_error(tmp_path):
    path = _write(tmp_path, "obstacles: [[0, 1]\nbounds: 3\n", "broken.yaml")
    message = _scene_error(path)
    assert "broken.yaml" in message and "YAML" in message


def test_python_tags_are_refused_not_executed(tmp_path):
    """yaml.safe_load must refuse python tags: this one would create a directory."""
    marker = tmp_path / "executed"
    path = _write(tmp_path, f"!!python/object/apply:os.mkdir [{str(marker)!r}]\n", "evil.yaml")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert not marker.exists()
    message = str(info.value)
    assert "evil.yaml" in message
    assert "\n" not in message, f"message is not one line: {message!r}"


def test_degenerate_design_is_a_scene_error_naming_the_parameter(tmp_path):
    values = PRESETS["table3"].to_dict()
    values["d"] = 1.6  # no longer than the part
    message = _scene_error(_write(tmp_path, {"feeder": {"design": values}}))
    assert "feeder" in message and "degenerate" in message and "d" in message


def test_out_of_range_design_value_names_the_parameter(tmp_path):
    values = PRESETS["table3"].to_dict()
    values["alpha"] = 2.0
    message = _scene_error(_write(tmp_path, {"feeder": {"design": values}}))
    assert "'alpha'" in message and "[0.05, 1.5708]" in message


def test_unknown_preset_lists_the_presets(tmp_path):
    message = _scene_error(_write(tmp_path, {"feeder": {"preset": "fig10"}}))
    assert "fig10" in message and all(name in message for name in PRESETS)


def test_derived_fields_are_refused_for_a_feeder(tmp_path):
    data = {"feeder": {"preset": "table3"}, "goal": FREE_FORM["goal"]}
    message = _scene_error(_write(tmp_path, data))
    assert "goal" in message


def test_bad_part_names_the_field_and_range(tmp_path):
    data = _with(part={"length": 2.0, "width": 3.0})
    message = _scene_error(_write(tmp_path, data))
    assert "width" in message and "[0.001, 2]" in message
    data = _with(part={"heavy_fraction": 0.2})
    message = _scene_error(_write(tmp_path, data))
    assert "heavy_fraction" in message and "[0.5, 1]" in message


def test_bad_polygon_names_the_obstacle(tmp_path):
    data = _with()
    data["obstacles"][0]["polygon"] = [[0, 0], [1, 0]]
    assert "obstacles[0].polygon" in _scene_error(_write(tmp_path, data))
    data["obstacles"][0]["polygon"] = [[0, 0], [1, 0], [2, math.nan]]
    assert "obstacles[0].polygon[2]" in _scene_error(_write(tmp_path, data))


def test_self_crossing_polygon_is_refused(tmp_path):
    """A bow tie is not a simple polygon: it has no interior to decompose (shapely agrees)."""
    bow_tie = [[0, 0], [3, 2], [3, 0], [0, 1]]
    assert not Polygon(bow_tie).is_valid
    data = _with()
    data["obstacles"][0]["polygon"] = bow_tie
    assert "obstacles[0].polygon" in _scene_error(_write(tmp_path, data))


def test_goal_yaw_outside_its_range_names_the_field(tmp_path):
    data = _with()
    data["goal"]["yaw_tol"] = 4.0
    message = _scene_error(_write(tmp_path, data))
    assert "goal.yaw_tol" in message and "3.14159" in message
