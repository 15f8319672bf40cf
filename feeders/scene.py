"""A scene: what every fidelity level needs to know about the world, as plain data.

Poses are ``(x, y, yaw)`` of the part's centre of mass, yaw along the part from its light end
to its heavy end (radians). Lengths in the paper's units, time in seconds, gravity in
length/s^2.

A scene names the part's orientations (:class:`OrientationClass`: a name and yaw windows, a
centre and a tolerance each); a yaw belongs to the class with the nearest centre among those
whose window holds it, else to :data:`OTHER_ORIENTATION`. The goal accepts one or more of
them. The feeder's scenes keep the peg's two, :data:`PEG_ORIENTATIONS` (heavy end down at
-pi/2, heavy end up at +pi/2, each +-pi/2: every yaw has one), and accept heavy end down.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from feeders.design import DesignParameters
from feeders.part import Peg
from feeders.shapes import Obstacles

Pose = tuple[float, float, float]

HEAVY_END_DOWN = "heavy end down"
HEAVY_END_UP = "heavy end up"
OTHER_ORIENTATION = "other orientation"  # a yaw in no class's window
MAX_CENTRES = 16  # yaw centres of one orientation class


def wrap_angle(angle: float) -> float:
    """Angle in [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


@dataclass(frozen=True)
class OrientationClass:
    """A named orientation of the part (for the cup: "open end up"): the yaws (rad) within
    ``tolerance`` of one of its ``centres`` (a class may have several: "on its side" is yaw 0
    and pi). Windows of different classes may overlap: :func:`orientation_of` gives the yaw to
    the class of the nearest centre."""

    name: str
    centres: tuple[float, ...]
    tolerance: float = math.pi

    def __post_init__(self) -> None:
        if not self.name or self.name == OTHER_ORIENTATION:
            raise ValueError(f"orientations: the name {self.name!r} is not allowed")
        if not 1 <= len(self.centres) <= MAX_CENTRES:
            raise ValueError(
                f"orientations.{self.name}: {len(self.centres)} yaws; give 1 to {MAX_CENTRES}"
            )
        for yaw in self.centres:
            if not (math.isfinite(yaw) and abs(yaw) <= math.pi):
                raise ValueError(
                    f"orientations.{self.name}.yaw = {yaw!r} is outside the range [-pi, pi]"
                )
        if not (math.isfinite(self.tolerance) and 0.0 < self.tolerance <= math.pi):
            raise ValueError(
                f"orientations.{self.name}.tolerance = {self.tolerance!r} is outside the range "
                "(0, pi]"
            )

    def distance(self, yaw: float) -> float:
        """How far (rad, in [0, pi]) ``yaw`` is from the nearest of the centres."""
        return min(abs(wrap_angle(yaw - c)) for c in self.centres)


PEG_ORIENTATIONS = (
    OrientationClass(HEAVY_END_DOWN, (-math.pi / 2,), math.pi / 2),
    OrientationClass(HEAVY_END_UP, (math.pi / 2,), math.pi / 2),
)
"""The peg's classes (the feeder's, and any scene's that names none): every yaw has one."""


def orientation_of(classes: tuple[OrientationClass, ...], yaw: float) -> str:
    """The class of ``yaw``: of the classes whose window holds it, the one with the nearest
    centre (the first listed on a tie); :data:`OTHER_ORIENTATION` when none holds it."""
    best, name = math.inf, OTHER_ORIENTATION
    for c in classes:
        d = c.distance(yaw)
        if d <= c.tolerance and d < best:
            best, name = d, c.name
    return name


@dataclass(frozen=True)
class Goal:
    """Goal region: the centre of mass inside a box and the yaw within ``yaw_tol`` of ``yaw``
    or within one of the ``more_yaws`` windows ``(centre, tolerance)``: a set of acceptable
    poses. ``orientations`` names the orientation classes the goal accepts (the scene's
    :class:`OrientationClass` names; a drop in the goal is one of them, the first unless its
    yaw's class is another of them).

    For the feeder: a box well inside the exit chute, heavy end down (``yaw = -pi/2``).
    ``target`` is the paper's q_goal (Eq. 10): the top-centre of the box, at ``yaw``.
    """

    x_min: float
    x_max: float
    y_min: float
    y_max: float
    yaw: float
    yaw_tol: float
    more_yaws: tuple[tuple[float, float], ...] = ()
    orientations: tuple[str, ...] = (HEAVY_END_DOWN,)

    def __post_init__(self) -> None:
        if not (self.x_min < self.x_max and self.y_min < self.y_max):
            raise ValueError("goal: need x_min < x_max and y_min < y_max")
        for _, tol in self.windows:
            if not 0.0 < tol <= math.pi:
                raise ValueError(f"goal: yaw_tol = {tol} is outside the range (0, pi]")
        if not self.orientations:
            raise ValueError("goal: it accepts at least one orientation class")

    @property
    def windows(self) -> tuple[tuple[float, float], ...]:
        """Every acceptable yaw window ``(centre, tolerance)`` (rad), ``(yaw, yaw_tol)`` first."""
        return ((self.yaw, self.yaw_tol), *self.more_yaws)

    @property
    def target(self) -> Pose:
        return (0.5 * (self.x_min + self.x_max), self.y_max, self.yaw)

    def position_gap(self, x: float, y: float) -> float:
        """Euclidean distance from (x, y) to the goal box (0 inside)."""
        dx = max(self.x_min - x, 0.0, x - self.x_max)
        dy = max(self.y_min - y, 0.0, y - self.y_max)
        return math.hypot(dx, dy)

    def yaw_gap(self, yaw: float) -> float:
        """How far (rad) the yaw is outside the nearest window (0 within one)."""
        return min(max(abs(wrap_angle(yaw - c)) - tol, 0.0) for c, tol in self.windows)

    def contains(self, pose: Pose) -> bool:
        return self.position_gap(pose[0], pose[1]) == 0.0 and self.yaw_gap(pose[2]) == 0.0


@dataclass(frozen=True)
class InputSet:
    """The bounded input sets of the levels (Eqs. 7-9).

    Geometric and kinematic levels: pose-increment rates ``|vx|, |vy| <= max_speed``
    (length/s) and ``|omega| <= max_turn`` (rad/s). Dynamic level: an external wrench on the
    part with ``|fx|, |fy| <= max_force`` (mass length/s^2) and ``|tau| <= max_torque``; zero
    makes that component passive (a zero-width control range).
    """

    max_speed: float = 1.0
    max_turn: float = 1.0
    max_force: float = 5.0  # half the default peg's weight: help, not a lift
    max_torque: float = 1.0

    def __post_init__(self) -> None:
        for name, low in (("max_speed", 0.0), ("max_turn", 0.0)):
            value = getattr(self, name)
            if not (math.isfinite(value) and low < value <= 1e3):
                raise ValueError(
                    f"inputs.{name} = {value!r} is outside the allowed range (0, 1000]"
                )
        for name in ("max_force", "max_torque"):
            value = getattr(self, name)
            if not (math.isfinite(value) and 0.0 <= value <= 1e3):
                raise ValueError(
                    f"inputs.{name} = {value!r} is outside the allowed range [0, 1000]"
                )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """U of the geometric and kinematic levels: (vx, vy, omega)."""
        high = np.array([self.max_speed, self.max_speed, self.max_turn])
        return -high, high

    def wrench_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """U of the dynamic level: (fx, fy, tau)."""
        high = np.array([self.max_force, self.max_force, self.max_torque])
        return -high, high


@dataclass(frozen=True)
class Scene:
    """Obstacles, the part, physical constants, start poses, goal and the state bounds.

    ``bounds`` are ``(x_min, x_max, y_min, y_max)`` for the centre of mass. ``friction`` is
    the Coulomb coefficient mu of every contact; ``restitution`` the coefficient e of the
    kinematic level's impacts (Stronge's energetic one: 0 plastic, 1 elastic; the dynamic
    level of the paper has none). ``outline`` is the
    free interior of a parametric feeder, a CCW polygon used for drawing (None for free-form
    scenes); ``design`` is the feeder's design when there is one. ``orientations`` are the
    part's named orientation classes (the peg's two unless given); the goal's
    ``orientations`` must be among them.
    """

    name: str
    obstacles: Obstacles
    part: Peg
    bounds: tuple[float, float, float, float]
    starts: dict[str, Pose]
    goal: Goal
    gravity: tuple[float, float] = (0.0, -9.81)
    friction: float = 0.3
    inputs: InputSet = field(default_factory=InputSet)
    restitution: float = 0.3
    design: DesignParameters | None = None
    outline: np.ndarray | None = None
    orientations: tuple[OrientationClass, ...] = PEG_ORIENTATIONS

    def __post_init__(self) -> None:
        names = [c.name for c in self.orientations]
        if not names or len(set(names)) != len(names):
            raise ValueError(f"orientations: expected distinct class names, got {names}")
        unknown = [n for n in self.goal.orientations if n not in names]
        if unknown:
            raise ValueError(
                f"goal.orientation: {unknown[0]!r} is not an orientation class of the part; "
                f"the classes are: {', '.join(names)}"
            )
        if not (math.isfinite(self.friction) and 0.0 <= self.friction <= 10.0):
            raise ValueError(f"friction = {self.friction!r} is outside the allowed range [0, 10]")
        if not (math.isfinite(self.restitution) and 0.0 <= self.restitution <= 1.0):
            raise ValueError(
                f"restitution = {self.restitution!r} is outside the allowed range [0, 1]"
            )

    def start(self, orientation: str) -> Pose:
        try:
            return self.starts[orientation]
        except KeyError:
            raise ValueError(
                f"unknown orientation '{orientation}'; this scene has: {', '.join(self.starts)}"
            ) from None

    def orientation_of(self, yaw: float) -> str:
        """The orientation class of ``yaw`` (:func:`orientation_of` over the scene's classes)."""
        return orientation_of(self.orientations, yaw)

    @property
    def orientation_names(self) -> tuple[str, ...]:
        """The classes' names, the goal's first (in its order), then the others (in the
        scene's order)."""
        accepted = self.goal.orientations
        return (*accepted, *(c.name for c in self.orientations if c.name not in accepted))
