"""Scenes read from YAML (``yaml.safe_load``), validated with errors naming field and range.

Two kinds, chosen by which key is present::

    feeder:                      # the parametric feeder
      preset: table3             # or: design: {a: 1.1, b: 1.1086, ..., f: [x, y], g: [x, y]}
    part: {length: 2.0, width: 1.0, mass: 1.0, heavy_fraction: 0.75}
    friction: 0.3
    restitution: 0.3             # the kinematic level's impacts (0 plastic .. 1 elastic)
    gravity: [0.0, -9.81]
    inputs: {max_speed: 1.0, max_turn: 1.0, max_force: 5.0, max_torque: 1.0}

    obstacles:                   # free-form: polygons (any simple polygon) and circles
      - polygon: [[-5, -1], [5, -1], [5, 0], [-5, 0]]
      - circle: {centre: [0, 2], radius: 0.5}
    bounds: [-5, 5, 0, 6]        # x_min, x_max, y_min, y_max of the centre of mass
    starts: {drop: [0, 4, 0]}    # name: [x, y, yaw]
    goal: {x: [-1, 1], y: [0, 1], yaw: 0.0, yaw_tol: 0.3}

Both may set ``name``, ``part``, ``friction``, ``restitution``, ``gravity`` and ``inputs``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from feeders.composite_part import CompositePart, part_from_dict
from feeders.cup import cup_part
from feeders.design import DesignError, DesignParameters, preset
from feeders.feeder import DEFAULT_FRICTION, DegenerateDesign, build_feeder
from feeders.fields import (
    FieldError,
    field_errors_as,
    mapping_field,
    name_field,
    number_field,
    numbers_field,
    read_yaml,
    shown_value,
)
from feeders.part import PartError, Peg
from feeders.scene import Goal, InputSet, Scene
from feeders.scene_checks import MAX_COORDINATE, MAX_STARTS, gravity_problem, scene_problems
from feeders.shapes import Obstacles, ShapeError, convex_pieces

MAX_VERTICES = 200  # points of one polygon: ear clipping is cubic in them (0.1 s at 200)
MAX_TOTAL_VERTICES = 2000  # points of all polygons: the whole scene clips in about a second
MAX_OBSTACLES = 1000


class SceneError(FieldError):
    """A scene file that cannot be read or is not valid; the message names the field."""


_TOP_KEYS = {
    "name",
    "feeder",
    "obstacles",
    "bounds",
    "starts",
    "goal",
    "part",
    "friction",
    "restitution",
    "gravity",
    "inputs",
}


PEG_KEYS = {"length", "width", "mass", "heavy_fraction"}
COMPOSITE_KEYS = {"pieces", "outline", "density"}
PACKAGED_PARTS = ("cup",)  # part: cup is feeders.cup.cup_part()


def _part(spec: Any, composite: bool = False) -> Peg | CompositePart:
    """The part of ``part:``: the two-density peg's keys (:data:`PEG_KEYS`; the default peg
    when absent), or, where ``composite`` parts are taken, a packaged part by name
    (:data:`PACKAGED_PARTS`) or the pieces of :func:`feeders.composite_part.part_from_dict`
    (:data:`COMPOSITE_KEYS`). Errors name the field as ``part...``."""
    if spec is None:
        return Peg.two_density()
    if composite and isinstance(spec, str):
        if spec == "cup":
            return cup_part()
        raise SceneError(
            f"part = {shown_value(spec)}: not a packaged part; packaged parts: "
            f"{', '.join(PACKAGED_PARTS)} (or give a mapping)"
        )
    if composite and isinstance(spec, dict) and set(spec) & COMPOSITE_KEYS:
        if set(spec) & PEG_KEYS:
            raise SceneError(
                f"part: give the peg's keys {sorted(PEG_KEYS)} or a composite part's "
                f"{sorted(COMPOSITE_KEYS)}, not both"
            )
        return part_from_dict(spec, "part.")
    spec = mapping_field(spec, "part", PEG_KEYS | (COMPOSITE_KEYS if composite else set()))
    args = {k: number_field(v, f"part.{k}") for k, v in spec.items()}
    try:
        return Peg.two_density(**args)
    except PartError as exc:
        raise SceneError(str(exc)) from None


def _inputs(spec: Any) -> InputSet:
    if spec is None:
        return InputSet()
    spec = mapping_field(spec, "inputs", {"max_speed", "max_turn", "max_force", "max_torque"})
    low = {"max_speed": 1e-9, "max_turn": 1e-9, "max_force": 0.0, "max_torque": 0.0}
    args = {k: number_field(v, f"inputs.{k}", low[k], 1e3) for k, v in spec.items()}
    return InputSet(**args)


def _design(spec: Any) -> DesignParameters:
    spec = mapping_field(spec, "feeder", {"preset", "design"})
    if ("preset" in spec) == ("design" in spec):
        raise SceneError("feeder: give exactly one of 'preset' or 'design'")
    try:
        if "preset" in spec:
            return preset(str(spec["preset"]))
        if not isinstance(spec["design"], dict):
            raise SceneError("feeder.design: expected a mapping of the 12 parameters")
        return DesignParameters.from_mapping(spec["design"])
    except DesignError as exc:
        raise SceneError(f"feeder: {exc}") from None


def _point(value: Any, field: str) -> list[float]:
    """An [x, y] point within the coordinates allowed (checked before any geometry: shapely
    and the ear clipping overflow on 1e308)."""
    x, y = numbers_field(value, field, 2)
    for name, v in (("x", x), ("y", y)):
        if abs(v) > MAX_COORDINATE:
            raise SceneError(f"{field}: {name} = {v:g} must lie within +-{MAX_COORDINATE:g}")
    return [x, y]


def _count_points(spec: list[Any]) -> None:
    """Refuse a polygon of more than ``MAX_VERTICES`` points, or more than
    ``MAX_TOTAL_VERTICES`` in all, before any geometry (ear clipping is cubic in them)."""
    total = 0
    for i, item in enumerate(spec):
        points = item.get("polygon") if isinstance(item, dict) else None
        if not isinstance(points, list):
            continue
        if len(points) > MAX_VERTICES:
            raise SceneError(
                f"obstacles[{i}].polygon: {len(points)} points; at most {MAX_VERTICES} are allowed"
            )
        total += len(points)
    if total > MAX_TOTAL_VERTICES:
        raise SceneError(
            f"obstacles: {total} polygon points in all; at most {MAX_TOTAL_VERTICES} are allowed"
        )


def _obstacles(spec: Any) -> Obstacles:
    if not isinstance(spec, list) or not spec:
        raise SceneError("obstacles: expected a non-empty list of {polygon: ...} or {circle: ...}")
    if len(spec) > MAX_OBSTACLES:
        raise SceneError(f"obstacles: {len(spec)} items; at most {MAX_OBSTACLES} are allowed")
    _count_points(spec)
    polygons, circles, labels_p, labels_c = [], [], [], []
    for i, item in enumerate(spec):
        field = f"obstacles[{i}]"
        item = mapping_field(item, field, {"polygon", "circle", "label"})
        label = name_field(item.get("label", field), f"{field}.label")
        if ("polygon" in item) == ("circle" in item):
            raise SceneError(f"{field}: give exactly one of 'polygon' or 'circle'")
        if "polygon" in item:
            pts = item["polygon"]
            if not isinstance(pts, list):
                raise SceneError(f"{field}.polygon: expected a list of [x, y] points")
            pts = [_point(p, f"{field}.polygon[{k}]") for k, p in enumerate(pts)]
            try:
                pieces = convex_pieces(pts, field=f"{field}.polygon")
            except ShapeError as exc:
                raise SceneError(str(exc)) from None
            polygons += pieces
            labels_p += [label] * len(pieces)
        else:
            c = mapping_field(item["circle"], f"{field}.circle", {"centre", "radius"})
            if "centre" not in c or "radius" not in c:
                raise SceneError(f"{field}.circle: needs 'centre' and 'radius'")
            cx, cy = _point(c["centre"], f"{field}.circle.centre")
            circles.append((cx, cy, number_field(c["radius"], f"{field}.circle.radius", 1e-9, 1e6)))
            labels_c.append(label)
    return Obstacles(
        tuple(polygons), np.array(circles, dtype=float).reshape(-1, 3), tuple(labels_p + labels_c)
    )


def _goal(spec: Any) -> Goal:
    spec = mapping_field(spec, "goal", {"x", "y", "yaw", "yaw_tol"})
    for key in ("x", "y", "yaw", "yaw_tol"):
        if key not in spec:
            raise SceneError(f"goal.{key} is required")
    x = numbers_field(spec["x"], "goal.x", 2)
    y = numbers_field(spec["y"], "goal.y", 2)
    if x[0] >= x[1] or y[0] >= y[1]:
        raise SceneError("goal.x and goal.y must be [low, high] with low < high")
    return Goal(
        x[0],
        x[1],
        y[0],
        y[1],
        number_field(spec["yaw"], "goal.yaw", -math.pi, math.pi),
        number_field(spec["yaw_tol"], "goal.yaw_tol", 1e-6, math.pi),
    )


def _gravity(value: Any, field: str) -> tuple[float, float]:
    gx, gy = numbers_field(value, field, 2)
    problem = gravity_problem((gx, gy), field)
    if problem:
        raise SceneError(problem)
    return gx, gy


ENVIRONMENT_KEYS = {"part", "friction", "restitution", "gravity", "inputs"}


def environment_from_dict(
    data: dict[str, Any], prefix: str = "", composite: bool = False
) -> dict[str, Any]:
    """What a feeder's scene needs besides its design, from the keys of
    :data:`ENVIRONMENT_KEYS` in ``data`` (others are ignored): keyword arguments of
    :func:`build_feeder` (``part``, ``inputs``, ``friction``, ``gravity``, ``restitution``).
    ``composite``: ``part`` may also be a composite part (a device family's; the feeder and
    scene files take the peg). Errors name the field with ``prefix`` before it."""
    try:
        return {
            "part": _part(data.get("part"), composite),
            "friction": number_field(
                data.get("friction", DEFAULT_FRICTION), f"{prefix}friction", 0.0, 10.0
            ),
            "restitution": number_field(
                data.get("restitution", 0.3), f"{prefix}restitution", 0.0, 1.0
            ),
            "gravity": _gravity(data.get("gravity", [0.0, -9.81]), f"{prefix}gravity"),
            "inputs": _inputs(data.get("inputs")),
        }
    except FieldError as exc:
        message = str(exc)
        if prefix and message.startswith(("part", "inputs")):
            message = prefix + message
        raise SceneError(message) from None


def scene_from_dict(data: Any, name: str = "scene", check: bool = True) -> Scene:
    """Validate a parsed YAML document and build its scene, physically sane
    (:func:`feeders.scene_checks.scene_problems`; ``check=False``: its fields only, for a
    caller that replaces the part and then calls :func:`checked_scene` itself)."""
    with field_errors_as(SceneError):
        scene = _scene_from_dict(data, name)
    return checked_scene(scene) if check else scene


def checked_scene(scene: Scene) -> Scene:
    """``scene`` if it is physically sane (:func:`feeders.scene_checks.scene_problems`), else
    :class:`SceneError` with the first problem: every reader of scenes (files, ``--design``)
    refuses the same things with the same words."""
    problems = scene_problems(scene)
    if problems:
        raise SceneError(problems[0])
    return scene


def _scene_from_dict(data: Any, name: str) -> Scene:
    data = mapping_field(data, "scene", _TOP_KEYS)
    name = name_field(data.get("name", name))
    env = environment_from_dict(data)
    part, friction, restitution = env["part"], env["friction"], env["restitution"]
    gravity, inputs = env["gravity"], env["inputs"]
    if ("feeder" in data) == ("obstacles" in data):
        raise SceneError(
            "scene: give exactly one of 'feeder' (parametric) or 'obstacles' (free-form)"
        )
    if "feeder" in data:
        extra = sorted({"bounds", "starts", "goal"} & set(data))
        if extra:
            raise SceneError(f"scene: {extra} are derived from the feeder design; remove them")
        try:
            return build_feeder(
                _design(data["feeder"]),
                part,
                inputs,
                friction,
                gravity,  # type: ignore[arg-type]
                name,
                restitution=restitution,
            )
        except DegenerateDesign as exc:
            raise SceneError(f"feeder: degenerate design: {exc}") from None
    for key in ("bounds", "starts", "goal"):
        if key not in data:
            raise SceneError(f"scene: '{key}' is required for a free-form scene")
    bounds = numbers_field(data["bounds"], "bounds", 4)
    if bounds[0] >= bounds[1] or bounds[2] >= bounds[3]:
        raise SceneError("bounds must be [x_min, x_max, y_min, y_max] with min < max")
    starts_spec = data["starts"]
    if not isinstance(starts_spec, dict) or not starts_spec:
        raise SceneError("starts: expected a mapping name: [x, y, yaw]")
    if len(starts_spec) > MAX_STARTS:
        raise SceneError(f"starts: {len(starts_spec)} poses; at most {MAX_STARTS} are allowed")
    starts = {str(k): tuple(numbers_field(v, f"starts.{k}", 3)) for k, v in starts_spec.items()}
    return Scene(
        name=name,
        obstacles=_obstacles(data["obstacles"]),
        part=part,
        bounds=tuple(bounds),  # type: ignore[arg-type]
        starts=starts,  # type: ignore[arg-type]
        goal=_goal(data["goal"]),
        gravity=gravity,  # type: ignore[arg-type]
        friction=friction,
        restitution=restitution,
        inputs=inputs,
    )


def load_scene(path: str | Path) -> Scene:
    """Read a scene file; any problem is a :class:`SceneError` naming the file and field."""
    path = Path(path)
    data = read_yaml(path, "scene", SceneError)
    try:
        return scene_from_dict(data, name=path.stem)
    except SceneError as exc:
        raise SceneError(f"{path}: {exc}") from None
