"""Device families: a parametric device written in YAML, built into a scene for any parameter
vector (issue 24).

The 12-parameter feeder of :mod:`feeders.feeder` is one device hard-coded in Python; a family
says the same kind of thing as data, with every coordinate an expression of named parameters
(:mod:`feeders.expressions`)::

    name: fig1
    parameters:                      # ordered: the order of the vector
      theta: {low: 0.3, high: 0.9, default: 0.5}     # rad
      pin_r: {low: 0.1, high: 0.4, default: 0.2}
    pieces:                          # obstacles, as in a scene file: convex polygons, circles
      - polygon: [[0, 0], ["4*cos(theta)", "4*sin(theta)"], ...]
        label: input chute floor
      - circle: {centre: [pin_x, pin_y], radius: pin_r}   # (or disc:)
    entries:                         # start pose (x, y, yaw) of the part's centre of mass
      open_leading: ["1 + 3*cos(theta)", "2 + 3*sin(theta)", theta]
    goal: {x: ["-b/2", "b/2"], y: [-3.7, -2.2], yaw: "-pi/2", yaw_tol: 0.35}
    rules:                           # when a vector cannot be built, and why
      - require: "pin_x + pin_r < 1.0"
        reason: the pin touches the wall below the lip
    bounds: [-2.5, 5, -4.4, 6]       # optional: x_min, x_max, y_min, y_max of the centre of mass
    part: {length: 2.2, width: 0.7}  # optional, as in a scene file, or a composite part
                                     # (``cup``, ``pieces``, ``outline``); also friction,
                                     # restitution, gravity, inputs
    orientations:                    # optional: the part's named orientation classes
      open end up: {yaw: "-pi/2", tolerance: "pi/4"}
      on its side: {yaw: [0, pi], tolerance: "pi/4"}

The goal may name the classes it accepts (``orientation: open end up``, or a list, with an
optional tighter ``yaw_tol``) in place of ``yaw`` and ``yaw_tol``.

A family is read once (:func:`family_from_dict`, :func:`load_family`): every expression is
compiled and may name only the family's parameters, and the default vector must build, else
one :class:`FamilyError` line naming the file and field. :meth:`DeviceFamily.build` then makes
the :class:`~feeders.scene.Scene` of any vector, or raises
:class:`~feeders.feeder.DegenerateDesign` with the reason (a failed rule's own words, a piece
that is not a convex polygon, a start inside the pieces...). Pure data and geometry, as the
rest of :mod:`feeders`.
"""

from __future__ import annotations

import keyword
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from importlib.resources import files
from pathlib import Path
from typing import Any, TypeAlias

import numpy as np
from shapely.geometry import LinearRing

from feeders.composite_part import CompositePart
from feeders.design import DesignSpace
from feeders.expressions import RESERVED, Expression, ExpressionError, compile_expression
from feeders.feeder import DEFAULT_FRICTION, DegenerateDesign
from feeders.fields import (
    FieldError,
    field_errors_as,
    mapping_field,
    name_field,
    number_field,
    numbers_field,
    read_yaml,
    shown,
    shown_value,
)
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import (
    MAX_CENTRES,
    OTHER_ORIENTATION,
    PEG_ORIENTATIONS,
    Goal,
    InputSet,
    OrientationClass,
    Pose,
    Scene,
    orientation_of,
    wrap_angle,
)
from feeders.scene_checks import MAX_COORDINATE, MAX_STARTS, scene_problems
from feeders.scene_yaml import ENVIRONMENT_KEYS, MAX_OBSTACLES, MAX_VERTICES, environment_from_dict
from feeders.shapes import Obstacles, is_convex, signed_area

MAX_PARAMETERS = 64
MAX_RULES = 100
MAX_ORIENTATIONS = 32  # named orientation classes of a family's part
MIN_AREA = 1e-9  # (length^2) a polygon piece of less area is degenerate

_TOP_KEYS = {
    "name",
    "parameters",
    "pieces",
    "entries",
    "goal",
    "rules",
    "bounds",
    "orientations",
} | ENVIRONMENT_KEYS


class FamilyError(FieldError):
    """A device family that cannot be read or whose default cannot be built; the message names
    the file and the field."""


@dataclass(frozen=True)
class Parameter:
    """A named design parameter of a family: its box ``[low, high]`` (what a sweep samples)
    and its ``default`` inside it."""

    name: str
    low: float
    high: float
    default: float


@dataclass(frozen=True)
class PolygonPiece:
    """A convex polygon obstacle whose vertices are expressions ``(x, y)``; either winding."""

    label: str
    vertices: tuple[tuple[Expression, Expression], ...]


@dataclass(frozen=True)
class DiscPiece:
    """A circle obstacle (a pin; ``circle:`` as in a scene file, or ``disc:``) with expressions
    for its centre and radius."""

    label: str
    centre: tuple[Expression, Expression]
    radius: Expression


Piece: TypeAlias = PolygonPiece | DiscPiece


@dataclass(frozen=True)
class Rule:
    """A condition every buildable vector satisfies, and the ``reason`` a vector that does not
    is refused with."""

    require: Expression
    reason: str


@dataclass(frozen=True)
class GoalSpec:
    """The exit region as expressions: the centre of mass in ``x`` x ``y`` (each ``(low,
    high)``), and either the yaw within ``yaw_tol`` of ``yaw`` (its class is the one holding
    ``yaw``) or, with ``orientations`` (class names), within ``yaw_tol`` (None: each class's
    tolerance) of any centre of those classes (:class:`feeders.scene.Goal`)."""

    x: tuple[Expression, Expression]
    y: tuple[Expression, Expression]
    yaw: Expression | None
    yaw_tol: Expression | None
    orientations: tuple[str, ...] = ()


def named_values(
    family: str, names: Sequence[str], vector: Mapping[str, float] | Sequence[float] | np.ndarray
) -> dict[str, float]:
    """``vector`` (a mapping of every name, or one number per name in ``names``' order) as a
    mapping of finite floats; ``ValueError`` naming ``family`` and the parameter otherwise."""
    if isinstance(vector, Mapping):
        unknown = sorted(set(map(str, vector)) - set(names))
        missing = [n for n in names if n not in vector]
        if unknown or missing:
            raise ValueError(
                f"{family}: parameters {shown(unknown)} are unknown and {missing} missing; "
                f"the family's parameters are {list(names)}"
            )
        raw = [vector[n] for n in names]
    else:
        raw = list(np.asarray(vector, dtype=float).reshape(-1))
        if len(raw) != len(names):
            raise ValueError(
                f"{family}: {len(raw)} values for {len(names)} parameters {list(names)}"
            )
    out = {}
    for name, value in zip(names, raw, strict=True):
        number = float(value)
        if not math.isfinite(number):
            raise ValueError(f"{family}: parameter {name} = {number!r} is not finite")
        out[name] = number
    return out


@dataclass(frozen=True)
class DeviceFamily:
    """A parametric device: named parameters with their box and defaults, pieces, entries
    (start pose per entry orientation), the exit goal, the rules of what can be built, the
    optional state bounds of its scenes, ``scene_bounds`` (x_min, x_max, y_min, y_max of the
    centre of mass; else the pieces' bounding box) and the environment a scene needs (part,
    friction, restitution, gravity, inputs)."""

    name: str
    parameters: tuple[Parameter, ...]
    pieces: tuple[Piece, ...]
    entries: tuple[tuple[str, tuple[Expression, Expression, Expression]], ...]
    goal: GoalSpec
    rules: tuple[Rule, ...] = ()
    scene_bounds: tuple[Expression, Expression, Expression, Expression] | None = None
    part: Peg | CompositePart = DEFAULT_PEG
    friction: float = DEFAULT_FRICTION
    restitution: float = 0.3
    gravity: tuple[float, float] = (0.0, -9.81)
    inputs: InputSet = field(default_factory=InputSet)
    orientations: tuple[OrientationClass, ...] = PEG_ORIENTATIONS

    @property
    def vector_names(self) -> tuple[str, ...]:
        """The parameters' names in the order of a vector."""
        return tuple(p.name for p in self.parameters)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)`` of the parameters' box, each shape (n,)."""
        return (
            np.array([p.low for p in self.parameters]),
            np.array([p.high for p in self.parameters]),
        )

    def space(self) -> DesignSpace:
        """The parameters' box as a :class:`~feeders.design.DesignSpace`, so
        :func:`feeders.halton.halton_points` samples it (``halton_points(n, seed,
        family.space())``)."""
        return DesignSpace(tuple((p.low, p.high) for p in self.parameters))

    def default(self) -> np.ndarray:
        """The default vector, shape (n,)."""
        return np.array([p.default for p in self.parameters])

    def values(
        self, vector: Mapping[str, float] | Sequence[float] | np.ndarray
    ) -> dict[str, float]:
        """``vector`` (a mapping of every parameter, or n numbers in :attr:`vector_names`
        order) as a mapping of finite floats; ``ValueError`` naming the parameter otherwise. A
        value may lie outside the box (a perturbation of a design at its edge): the rules say
        what can be built."""
        return named_values(self.name, self.vector_names, vector)

    def made_bounds(self) -> None:
        """What a made device's values are kept within: nothing for a family (its rules
        decide what can be built; :func:`experiments.drop.perturbations.toleranced_values`)."""
        return None

    def build(self, vector: Mapping[str, float] | Sequence[float] | np.ndarray) -> Scene:
        """The scene of this parameter vector, or :class:`DegenerateDesign` with the reason and
        the parameters involved: the first rule that fails (in order), an expression that cannot
        be evaluated there, a piece that is not a convex polygon of positive area or a disc of
        positive radius, a goal box of no size, or a scene that is not physically sane
        (:func:`feeders.scene_checks.scene_problems`: a start pose inside the pieces...)."""
        values = self.values(vector)
        try:
            return self._build(values)
        except ExpressionError as exc:
            raise DegenerateDesign(str(exc), self.vector_names) from None

    def _build(self, values: dict[str, float]) -> Scene:
        for rule in self.rules:
            if not rule.require.holds(values):
                raise DegenerateDesign(rule.reason, _ordered(rule.require.names, self))
        polygons: list[np.ndarray] = []
        circles: list[tuple[float, float, float]] = []
        labels_p: list[str] = []
        labels_c: list[str] = []
        for piece in self.pieces:
            if isinstance(piece, PolygonPiece):
                polygons.append(self._polygon(piece, values))
                labels_p.append(piece.label)
            else:
                cx, cy = (e.evaluate(values) for e in piece.centre)
                radius = piece.radius.evaluate(values)
                names = _ordered(piece.radius.names | _names(piece.centre), self)
                if radius <= 0.0:
                    raise DegenerateDesign(
                        f"{piece.label}: radius {radius:g} is not positive", names
                    )
                circles.append((cx, cy, radius))
                labels_c.append(piece.label)
        starts: dict[str, Pose] = {
            name: (pose[0].evaluate(values), pose[1].evaluate(values), pose[2].evaluate(values))
            for name, pose in self.entries
        }
        goal = self._goal(values)
        obstacles = Obstacles(
            tuple(polygons),
            np.array(circles, dtype=float).reshape(-1, 3),
            tuple(labels_p + labels_c),
        )
        scene = Scene(
            name=self.name,
            obstacles=obstacles,
            # Scene.part is typed Peg until the levels take a CompositePart (issue 24)
            part=self.part,  # type: ignore[arg-type]
            bounds=self._bounds(values, obstacles),
            starts=starts,
            goal=goal,
            gravity=self.gravity,
            friction=self.friction,
            inputs=self.inputs,
            restitution=self.restitution,
            orientations=self.orientations,
        )
        problems = scene_problems(scene)
        if problems:
            raise DegenerateDesign(problems[0], self.vector_names)
        return scene

    def _goal(self, values: dict[str, float]) -> Goal:
        """The goal at ``values``: its box, its yaw windows and the classes it accepts."""
        spec = self.goal
        tol_exprs = () if spec.yaw_tol is None else (spec.yaw_tol,)
        yaw_exprs = () if spec.yaw is None else (spec.yaw,)
        goal_values = [e.evaluate(values) for e in (*spec.x, *spec.y)]
        names = _ordered(_names((*spec.x, *spec.y, *yaw_exprs, *tol_exprs)), self)
        if not (goal_values[0] < goal_values[1] and goal_values[2] < goal_values[3]):
            raise DegenerateDesign(
                f"goal: the box x {goal_values[:2]}, y {goal_values[2:]} has no size", names
            )
        tol = None if spec.yaw_tol is None else spec.yaw_tol.evaluate(values)
        if spec.yaw is not None:
            yaw = spec.yaw.evaluate(values)
            if not (tol is not None and 0.0 < tol <= math.pi and abs(yaw) <= math.pi):
                raise DegenerateDesign(
                    f"goal: yaw = {yaw:g} must lie in [-pi, pi] and yaw_tol = {tol:g} in (0, pi]",
                    names,
                )
            accepted: tuple[str, ...] = (orientation_of(self.orientations, yaw),)
            if accepted[0] == OTHER_ORIENTATION:
                raise DegenerateDesign(
                    f"goal: yaw = {yaw:g} lies in no orientation class of the part "
                    f"({', '.join(c.name for c in self.orientations)}); widen a class or "
                    "name the goal's class (goal.orientation)",
                    names,
                )
            windows = [(yaw, tol)]
        else:
            if tol is not None and not 0.0 < tol <= math.pi:
                raise DegenerateDesign(f"goal: yaw_tol = {tol:g} must lie in (0, pi]", names)
            accepted = spec.orientations
            by_name = {c.name: c for c in self.orientations}
            windows = [
                (centre, by_name[n].tolerance if tol is None else tol)
                for n in accepted
                for centre in by_name[n].centres
            ]
        x_min, x_max, y_min, y_max = goal_values
        (yaw0, tol0), *more = windows
        return Goal(x_min, x_max, y_min, y_max, yaw0, tol0, tuple(more), accepted)

    def _polygon(self, piece: PolygonPiece, values: dict[str, float]) -> np.ndarray:
        """The piece's vertices, counter-clockwise, checked convex, simple and of area."""
        vertices = np.array([[x.evaluate(values), y.evaluate(values)] for x, y in piece.vertices])
        names = _ordered(_names(e for xy in piece.vertices for e in xy), self)
        if np.abs(vertices).max() > MAX_COORDINATE:
            raise DegenerateDesign(
                f"{piece.label}: a vertex lies beyond +-{MAX_COORDINATE:g}", names
            )
        area = signed_area(vertices)
        if abs(area) < MIN_AREA:
            raise DegenerateDesign(f"{piece.label}: the polygon has zero area", names)
        if not LinearRing(vertices).is_simple:
            raise DegenerateDesign(f"{piece.label}: the polygon crosses itself", names)
        if area < 0:
            vertices = vertices[::-1].copy()
        if not is_convex(vertices, tol=1e-9):
            raise DegenerateDesign(f"{piece.label}: the polygon is not convex", names)
        return vertices

    def _bounds(
        self, values: dict[str, float], obstacles: Obstacles
    ) -> tuple[float, float, float, float]:
        if self.scene_bounds is not None:
            x0, x1, y0, y1 = (e.evaluate(values) for e in self.scene_bounds)
            if not (x0 < x1 and y0 < y1):
                raise DegenerateDesign(
                    f"bounds = {[x0, x1, y0, y1]}: need x_min < x_max and y_min < y_max",
                    _ordered(_names(self.scene_bounds), self),
                )
            return (x0, x1, y0, y1)
        points = [p for p in obstacles.polygons]
        for cx, cy, radius in obstacles.circles:
            points.append(np.array([[cx - radius, cy - radius], [cx + radius, cy + radius]]))
        stacked = np.concatenate(points)
        low, high = stacked.min(axis=0), stacked.max(axis=0)
        return (float(low[0]), float(high[0]), float(low[1]), float(high[1]))


def _names(expressions: Any) -> frozenset[str]:
    return frozenset().union(*(e.names for e in expressions))


def _ordered(names: frozenset[str], family: DeviceFamily) -> tuple[str, ...]:
    """``names`` in the family's parameter order (for :class:`DegenerateDesign`)."""
    return tuple(n for n in family.vector_names if n in names)


def _parameters(spec: Any, prefix: str) -> tuple[Parameter, ...]:
    field_name = f"{prefix}parameters"
    if not isinstance(spec, dict) or not spec:
        raise FamilyError(f"{field_name}: expected a mapping name: {{low, high, default}}")
    if len(spec) > MAX_PARAMETERS:
        raise FamilyError(
            f"{field_name}: {len(spec)} parameters; at most {MAX_PARAMETERS} are allowed"
        )
    out = []
    for name, item in spec.items():
        where = f"{field_name}.{shown(name)}"
        if (
            not isinstance(name, str)
            or not name.isidentifier()
            or not name.isascii()
            or keyword.iskeyword(name)
            or name in RESERVED
        ):
            raise FamilyError(
                f"{where}: a parameter name is an ASCII identifier (letters, digits, _), not a "
                "Python keyword and not one of the language's names "
                f"({', '.join(sorted(RESERVED))})"
            )
        item = mapping_field(item, where, {"low", "high", "default"})
        for key in ("low", "high", "default"):
            if key not in item:
                raise FamilyError(f"{where}.{key} is required")
        low = number_field(item["low"], f"{where}.low", -MAX_COORDINATE, MAX_COORDINATE)
        high = number_field(item["high"], f"{where}.high", -MAX_COORDINATE, MAX_COORDINATE)
        if not low < high:
            raise FamilyError(f"{where}: need low < high, got low = {low:g}, high = {high:g}")
        default = number_field(item["default"], f"{where}.default", low, high)
        out.append(Parameter(name, low, high, default))
    return tuple(out)


def _pair(value: Any, field_name: str, known: tuple[str, ...]) -> tuple[Expression, Expression]:
    if not isinstance(value, list) or len(value) != 2:
        raise FamilyError(f"{field_name}: expected [x, y], two numbers or expressions")
    return (
        compile_expression(value[0], f"{field_name}[0]", known),
        compile_expression(value[1], f"{field_name}[1]", known),
    )


CIRCLE_KEYS = ("circle", "disc")  # a scene file's word first; "disc" kept for fig1.yaml


def _pieces(spec: Any, prefix: str, known: tuple[str, ...]) -> tuple[Piece, ...]:
    """The obstacles, in a scene file's words: ``{polygon: [[x, y], ...]}`` (convex) or
    ``{circle: {centre: [x, y], radius: r}}`` (``disc:`` is accepted for ``circle:``), each
    with an optional ``label``."""
    field_name = f"{prefix}pieces"
    if not isinstance(spec, list) or not spec:
        raise FamilyError(
            f"{field_name}: expected a non-empty list of {{polygon: ...}} or {{circle: ...}}"
        )
    if len(spec) > MAX_OBSTACLES:
        raise FamilyError(f"{field_name}: {len(spec)} pieces; at most {MAX_OBSTACLES} are allowed")
    pieces: list[Piece] = []
    for i, item in enumerate(spec):
        where = f"{field_name}[{i}]"
        item = mapping_field(item, where, {"polygon", *CIRCLE_KEYS, "label"})
        label = name_field(item.get("label", where), f"{where}.label")
        shapes = [k for k in ("polygon", *CIRCLE_KEYS) if k in item]
        if len(shapes) != 1:
            raise FamilyError(f"{where}: give exactly one of 'polygon' or 'circle'")
        if "polygon" in item:
            points = item["polygon"]
            if not isinstance(points, list) or not 3 <= len(points) <= MAX_VERTICES:
                raise FamilyError(
                    f"{where}.polygon: expected a list of 3 to {MAX_VERTICES} [x, y] points "
                    "of a convex polygon"
                )
            vertices = tuple(_pair(p, f"{where}.polygon[{k}]", known) for k, p in enumerate(points))
            pieces.append(PolygonPiece(label, vertices))
        else:
            key = f"{where}.{shapes[0]}"
            circle = mapping_field(item[shapes[0]], key, {"centre", "radius"})
            if "centre" not in circle or "radius" not in circle:
                raise FamilyError(f"{key}: needs 'centre' and 'radius'")
            centre = _pair(circle["centre"], f"{key}.centre", known)
            radius = compile_expression(circle["radius"], f"{key}.radius", known)
            pieces.append(DiscPiece(label, centre, radius))
    return tuple(pieces)


def _entries(
    spec: Any, prefix: str, known: tuple[str, ...]
) -> tuple[tuple[str, tuple[Expression, Expression, Expression]], ...]:
    field_name = f"{prefix}entries"
    if not isinstance(spec, dict) or not spec:
        raise FamilyError(f"{field_name}: expected a mapping orientation: [x, y, yaw]")
    if len(spec) > MAX_STARTS:
        raise FamilyError(f"{field_name}: {len(spec)} entries; at most {MAX_STARTS} are allowed")
    out = []
    for name, pose in spec.items():
        where = f"{field_name}.{name_field(name, f'{field_name} name')}"
        if not isinstance(pose, list) or len(pose) != 3:
            raise FamilyError(f"{where}: expected [x, y, yaw], three numbers or expressions")
        x, y, yaw = (compile_expression(v, f"{where}[{k}]", known) for k, v in enumerate(pose))
        out.append((str(name), (x, y, yaw)))
    return tuple(out)


def _goal(
    spec: Any, prefix: str, known: tuple[str, ...], classes: tuple[OrientationClass, ...]
) -> GoalSpec:
    where = f"{prefix}goal"
    spec = mapping_field(spec, where, {"x", "y", "yaw", "yaw_tol", "orientation"})
    for key in ("x", "y"):
        if key not in spec:
            raise FamilyError(f"{where}.{key} is required")
    x, y = _pair(spec["x"], f"{where}.x", known), _pair(spec["y"], f"{where}.y", known)
    tol = spec.get("yaw_tol")
    yaw_tol = None if tol is None else compile_expression(tol, f"{where}.yaw_tol", known)
    if "orientation" not in spec:
        if "yaw" in spec and yaw_tol is None:
            raise FamilyError(f"{where}.yaw_tol is required with {where}.yaw")
        if "yaw" not in spec and yaw_tol is not None:
            raise FamilyError(f"{where}.yaw is required (or {where}.orientation) with yaw_tol")
        if "yaw" not in spec:
            raise FamilyError(
                f"{where}: give 'yaw' and 'yaw_tol', or 'orientation' (the classes it accepts, "
                "of the part's orientations) with an optional 'yaw_tol'"
            )
        yaw = compile_expression(spec["yaw"], f"{where}.yaw", known)
        return GoalSpec(x, y, yaw, yaw_tol)
    if "yaw" in spec:
        raise FamilyError(f"{where}: give 'yaw' or 'orientation', not both")
    names = spec["orientation"]
    names = names if isinstance(names, list) else [names]
    allowed = [c.name for c in classes]
    if not names:
        raise FamilyError(f"{where}.orientation: name one or more of: {', '.join(allowed)}")
    for name in names:
        if name not in allowed:
            raise FamilyError(
                f"{where}.orientation = {shown_value(name)}: not an orientation class of the "
                f"part; the classes are: {', '.join(allowed)} (see orientations)"
            )
    return GoalSpec(x, y, None, yaw_tol, tuple(dict.fromkeys(names)))


def _orientations(spec: Any, prefix: str) -> tuple[OrientationClass, ...]:
    """The part's orientation classes: name -> {yaw: centre or [centres], tolerance} (rad,
    numbers or expressions of constants; tolerance in (0, pi], default pi)."""
    field_name = f"{prefix}orientations"
    if spec is None:
        return PEG_ORIENTATIONS
    if not isinstance(spec, dict) or not spec:
        raise FamilyError(
            f"{field_name}: expected a mapping name: {{yaw: centre or [centres], tolerance}}"
        )
    if len(spec) > MAX_ORIENTATIONS:
        raise FamilyError(
            f"{field_name}: {len(spec)} classes; at most {MAX_ORIENTATIONS} are allowed"
        )
    out = []
    for name, item in spec.items():
        label = name_field(name, f"{field_name} name")
        where = f"{field_name}.{label}"
        if label == OTHER_ORIENTATION:
            raise FamilyError(
                f"{where}: '{OTHER_ORIENTATION}' is the class of a yaw in no window; "
                "name the class otherwise"
            )
        item = mapping_field(item, where, {"yaw", "face_down", "tolerance"})
        if ("yaw" in item) == ("face_down" in item):
            raise FamilyError(
                f"{where}: give one of 'yaw' (a centre or a list of centres, rad) or "
                "'face_down' (a face of the part, [[x, y], [x, y]], or a list of faces)"
            )
        if "face_down" in item:
            centres = _faces_down(item["face_down"], f"{where}.face_down")
        else:
            yaws = item["yaw"] if isinstance(item["yaw"], list) else [item["yaw"]]
            if not 1 <= len(yaws) <= MAX_CENTRES:
                raise FamilyError(f"{where}.yaw: give 1 to {MAX_CENTRES} centres")
            centres = tuple(
                _constant(v, f"{where}.yaw" + (f"[{k}]" if isinstance(item["yaw"], list) else ""))
                for k, v in enumerate(yaws)
            )
        for k, centre in enumerate(centres):
            if abs(centre) > math.pi + 1e-12:
                raise FamilyError(
                    f"{where}.yaw = {centre:g} is outside the allowed range [-pi, pi]"
                    + (f" (centre {k})" if len(centres) > 1 else "")
                )
        tolerance = _constant(item.get("tolerance", math.pi), f"{where}.tolerance")
        if not 0.0 < tolerance <= math.pi + 1e-12:
            raise FamilyError(
                f"{where}.tolerance = {tolerance:g} is outside the allowed range (0, pi]"
            )
        centres = tuple(max(-math.pi, min(math.pi, c)) for c in centres)
        out.append(OrientationClass(label, centres, min(tolerance, math.pi)))
    return tuple(out)


def _faces_down(spec: Any, field_name: str) -> tuple[float, ...]:
    """The yaws that put each face down: a face is a segment of the part's outline in the
    part's frame, ``[[x1, y1], [x2, y2]]``, listed with the part on its left (counter-
    clockwise along the outline, as a polygon piece's edges run), so its outward normal is
    (y2 - y1, x1 - x2) / length; the yaw turns that normal to (0, -1), gravity's way. The
    cup's base: ``[[0.9, -0.5], [0.9, 0.5]]``, yaw -pi/2."""
    single = (
        isinstance(spec, list)
        and len(spec) == 2
        and all(isinstance(p, list) and len(p) == 2 and not isinstance(p[0], list) for p in spec)
    )
    faces = [spec] if single else spec
    if not isinstance(faces, list) or not 1 <= len(faces) <= MAX_CENTRES:
        raise FamilyError(
            f"{field_name}: expected a face [[x, y], [x, y]] or a list of 1 to {MAX_CENTRES}"
        )
    out = []
    for k, face in enumerate(faces):
        where = field_name if single else f"{field_name}[{k}]"
        if not (
            isinstance(face, list) and len(face) == 2 and all(isinstance(q, list) for q in face)
        ):
            raise FamilyError(f"{where}: expected a face [[x, y], [x, y]] (two points)")
        with field_errors_as(FamilyError):
            points = [numbers_field(p, f"{where}[{i}]", 2) for i, p in enumerate(face)]
        (x1, y1), (x2, y2) = points
        length = math.hypot(x2 - x1, y2 - y1)
        if not length > 0.0:
            raise FamilyError(f"{where}: the two points are the same; a face has a length")
        nx, ny = (y2 - y1) / length, (x1 - x2) / length
        out.append(wrap_angle(-0.5 * math.pi - math.atan2(ny, nx)))
    return tuple(out)


def _constant(value: Any, field_name: str) -> float:
    """A number or an expression of constants (``"-pi/2"``), its value."""
    return compile_expression(value, field_name, ()).evaluate({})


def _rules(spec: Any, prefix: str, known: tuple[str, ...]) -> tuple[Rule, ...]:
    field_name = f"{prefix}rules"
    if spec is None:
        return ()
    if not isinstance(spec, list):
        raise FamilyError(f"{field_name}: expected a list of {{require: condition, reason: text}}")
    if len(spec) > MAX_RULES:
        raise FamilyError(f"{field_name}: {len(spec)} rules; at most {MAX_RULES} are allowed")
    out = []
    for i, item in enumerate(spec):
        where = f"{field_name}[{i}]"
        item = mapping_field(item, where, {"require", "reason"})
        if "require" not in item or "reason" not in item:
            raise FamilyError(f"{where}: needs 'require' (a condition) and 'reason' (text)")
        reason = item["reason"]
        if not isinstance(reason, str) or not 1 <= len(reason.strip()) <= 300:
            raise FamilyError(f"{where}.reason: expected text of 1 to 300 characters")
        if any(c in reason for c in "\n\r"):
            raise FamilyError(f"{where}.reason: one line of text (no line breaks)")
        require = compile_expression(item["require"], f"{where}.require", known, condition=True)
        out.append(Rule(require, reason.strip()))
    return tuple(out)


def _bounds_spec(
    spec: Any, prefix: str, known: tuple[str, ...]
) -> tuple[Expression, Expression, Expression, Expression] | None:
    if spec is None:
        return None
    where = f"{prefix}bounds"
    if not isinstance(spec, list) or len(spec) != 4:
        raise FamilyError(f"{where}: expected [x_min, x_max, y_min, y_max], numbers or expressions")
    x0, x1, y0, y1 = (compile_expression(v, f"{where}[{k}]", known) for k, v in enumerate(spec))
    return (x0, x1, y0, y1)


def family_from_dict(data: Any, prefix: str = "", name: str = "family") -> DeviceFamily:
    """Read a family from a parsed YAML mapping; every field is checked and every expression
    compiled against the parameters (errors name the field with ``prefix`` before it), and
    the default vector must build (else :class:`FamilyError` with the reason)."""
    with field_errors_as(FamilyError):
        family = _family(data, prefix, name)
    try:
        family.build(family.default())
    except DegenerateDesign as exc:
        defaults = ", ".join(f"{p.name} = {p.default:g}" for p in family.parameters)
        raise FamilyError(
            f"{prefix}parameters: the defaults ({defaults}) cannot be built: {exc.reason}; "
            "the defaults must satisfy every rule and give valid pieces, entries and goal"
        ) from None
    return family


def _family(data: Any, prefix: str, name: str) -> DeviceFamily:
    data = mapping_field(data, prefix.rstrip(".") or "family", _TOP_KEYS)
    for key in ("parameters", "pieces", "entries", "goal"):
        if key not in data:
            raise FamilyError(f"{prefix}{key} is required")
    family_name = name_field(data.get("name", name), f"{prefix}name")
    parameters = _parameters(data["parameters"], prefix)
    known = tuple(p.name for p in parameters)
    env = environment_from_dict(data, prefix, composite=True)
    classes = _orientations(data.get("orientations"), prefix)
    return DeviceFamily(
        name=family_name,
        parameters=parameters,
        pieces=_pieces(data["pieces"], prefix, known),
        entries=_entries(data["entries"], prefix, known),
        goal=_goal(data["goal"], prefix, known, classes),
        rules=_rules(data.get("rules"), prefix, known),
        scene_bounds=_bounds_spec(data.get("bounds"), prefix, known),
        part=env["part"],
        friction=env["friction"],
        restitution=env["restitution"],
        gravity=env["gravity"],
        inputs=env["inputs"],
        orientations=classes,
    )


PACKAGED_FOLDER = "families"  # feeders/families/<name>.yaml, package data of the wheel


def packaged_families() -> list[str]:
    """The names of the families packaged with partfeeder (``fig1``, ``fig1-cup``, ...)."""
    found = files("feeders").joinpath(PACKAGED_FOLDER).iterdir()
    return sorted(e.name[: -len(".yaml")] for e in found if e.name.endswith(".yaml"))


def packaged_family(name: str) -> Path | None:
    """The file of the family packaged as ``name`` (``fig1-cup`` or ``fig1-cup.yaml``), read
    through importlib.resources so that it is found from an installed wheel in any directory;
    None when there is no such family."""
    name = name[: -len(".yaml")] if name.endswith(".yaml") else name
    if name not in packaged_families():
        return None
    return Path(str(files("feeders").joinpath(PACKAGED_FOLDER, f"{name}.yaml")))


def load_family(path: str | Path) -> DeviceFamily:
    """Read a family file; any problem is one :class:`FamilyError` line naming the file and
    the field."""
    path = Path(path)
    data = read_yaml(path, "device family", FamilyError)
    try:
        return family_from_dict(data, name=path.stem)
    except FamilyError as exc:
        raise FamilyError(f"{shown(path)}: {exc}") from None
