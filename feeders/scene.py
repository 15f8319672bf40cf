"""A scene: what every fidelity level needs to know about the world, as plain data.

Poses are ``(x, y, yaw)`` of the part's centre of mass, yaw along the part from its light end
to its heavy end (radians). Lengths in the paper's units, time in seconds, gravity in
length/s^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from feeders.design import DesignParameters
from feeders.part import Peg
from feeders.shapes import Obstacles

Pose = tuple[float, float, float]


def wrap_angle(angle: float) -> float:
    """Angle in [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


@dataclass(frozen=True)
class Goal:
    """Goal region: the centre of mass inside a box and the yaw within ``yaw_tol`` of ``yaw``.

    For the feeder: a box well inside the exit chute, heavy end down (``yaw = -pi/2``).
    ``target`` is the paper's q_goal (Eq. 10): the top-centre of the box, at that yaw.
    """

    x_min: float
    x_max: float
    y_min: float
    y_max: float
    yaw: float
    yaw_tol: float

    def __post_init__(self) -> None:
        if not (self.x_min < self.x_max and self.y_min < self.y_max):
            raise ValueError("goal: need x_min < x_max and y_min < y_max")
        if not 0.0 < self.yaw_tol <= math.pi:
            raise ValueError(f"goal: yaw_tol = {self.yaw_tol} is outside the range (0, pi]")

    @property
    def target(self) -> Pose:
        return (0.5 * (self.x_min + self.x_max), self.y_max, self.yaw)

    def position_gap(self, x: float, y: float) -> float:
        """Euclidean distance from (x, y) to the goal box (0 inside)."""
        dx = max(self.x_min - x, 0.0, x - self.x_max)
        dy = max(self.y_min - y, 0.0, y - self.y_max)
        return math.hypot(dx, dy)

    def yaw_gap(self, yaw: float) -> float:
        """How far (rad) the yaw is outside the tolerance (0 within it)."""
        return max(abs(wrap_angle(yaw - self.yaw)) - self.yaw_tol, 0.0)

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
    scenes); ``design`` is the feeder's design when there is one.
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

    def __post_init__(self) -> None:
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
