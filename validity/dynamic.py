"""The dynamic level (paper Eq. 7): rigid-body dynamics with Coulomb friction and gravity.

State: pose and velocity ``(x, y, theta, vx, vy, omega)`` of the part's centre of mass. Input:
a constant external wrench ``(fx, fy, tau)`` from the scene's bounded set (zero bounds make
the part passive). Motion: Stewart-Trinkle time stepping at step ``h``
(:mod:`validity.stewart_trinkle`), compiled as one loop per propagation or trajectory.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from feeders.scene import Scene
from validity.moving_part import MovingPartLevel, check_ranges, run_buffers
from validity.stewart_trinkle import (
    END_REASONS,
    SUMMARY_FIELDS,
    TELEMETRY_COLUMNS,
    simulate_kernel,
)

DEFAULT_STEP = 1e-3  # h (s): first-order error a T h / 2 (about 1 mm over 1 s of sliding)
DEFAULT_MARGIN = 0.005  # contacts closer than this (+ 2 h |speed|) enter the LCP (length)
PUSH_CAP = 0.5  # fastest (length/s) a pose correction moves any point of the part out of an overlap
VELOCITY_LIMIT = 20.0  # |vx|, |vy| (length/s) and |omega| (rad/s) of a valid state
PENETRATION_TOLERANCE = 0.01  # deepest overlap (length) a valid dynamic state may have


def _wrap_outside(yaw: np.ndarray) -> np.ndarray:
    """Yaw wrapped into [-pi, pi) where it lies outside, untouched inside: a propagation
    continued from its own result then repeats the same arithmetic (chained calls stay exact)."""
    outside = (yaw < -math.pi) | (yaw >= math.pi)
    return np.where(outside, (yaw + math.pi) % (2.0 * math.pi) - math.pi, yaw)


def _rest_steps(rest_speed: float, rest_time: float, h: float) -> int:
    """Steps of stillness that end a run at rest (0: never ends at rest)."""
    return math.ceil(rest_time / h) if rest_speed > 0.0 else 0


@dataclass(frozen=True)
class Trajectory:
    """A simulated run: states at ``times`` (rows x, y, theta, vx, vy, omega), per-step
    telemetry (columns ``TELEMETRY_COLUMNS``), totals, and why it ended (``END_REASONS``)."""

    times: np.ndarray = field(repr=False)
    states: np.ndarray = field(repr=False)
    telemetry: np.ndarray = field(repr=False)
    summary: dict
    end: str
    h: float
    mass: float
    inertia: float
    gravity: tuple[float, float]
    rest_steps: int = 0  # length of the still window that ends a run "at_rest" (steps)

    @property
    def final(self) -> np.ndarray:
        return self.states[-1]

    @property
    def settle_index(self) -> int:
        """Row of Eq. 10's T: where the still window began for a run that ended at rest (the
        part came to rest then; the window only confirms it), else the last row."""
        if self.end == "at_rest":
            return max(len(self.states) - 1 - self.rest_steps, 0)
        return len(self.states) - 1

    @property
    def duration(self) -> float:
        return float(self.times[-1])

    def energy(self) -> np.ndarray:
        """Kinetic plus gravitational potential energy at every state (mass length^2/s^2)."""
        s = self.states
        kinetic = 0.5 * self.mass * (s[:, 3] ** 2 + s[:, 4] ** 2)
        kinetic += 0.5 * self.inertia * s[:, 5] ** 2
        potential = -self.mass * (self.gravity[0] * s[:, 0] + self.gravity[1] * s[:, 1])
        return kinetic + potential

    def energy_rise(self) -> float:
        """Largest rise of the energy above its starting value (0 when it never rises)."""
        e = self.energy()
        return float(max(0.0, np.max(e - e[0])))


class DynamicLevel(MovingPartLevel):
    """Eq. 7 on a scene: validity, clearance, propagation and simulation of (pose, velocity)."""

    name = "dynamic"
    velocity_limit = VELOCITY_LIMIT

    def __init__(
        self,
        scene: Scene,
        step: float = DEFAULT_STEP,
        margin: float = DEFAULT_MARGIN,
        push_cap: float = PUSH_CAP,
        skip_free: bool = True,
        warm_start: bool = True,
        penetration_tolerance: float = PENETRATION_TOLERANCE,
    ):
        check_ranges(
            "dynamic",
            (
                ("step h", step, 1e-6, 0.1),
                ("contact margin", margin, 0.0, 1.0),
                ("push-out cap", push_cap, 1e-6, 1e3),
                ("penetration tolerance", penetration_tolerance, 0.0, 1.0),
            ),
        )
        super().__init__(scene)
        self.step = float(step)
        self.margin = float(margin)
        self.push_cap = float(push_cap)
        self.skip_free = bool(skip_free)
        self.warm_start = bool(warm_start)
        self.penetration_tolerance = float(penetration_tolerance)
        self.gravity = np.asarray(scene.gravity, dtype=np.float64)

    def control_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.scene.inputs.wrench_bounds()

    def _run(
        self,
        state: Sequence[float],
        wrench: Sequence[float],
        duration: float,
        y_stop: float,
        rest_speed: float,
        rest_time: float,
        record: bool,
    ):
        n, h = self.steps_of(duration)
        out, traj, tele, summary = run_buffers(
            n, record, len(TELEMETRY_COLUMNS), len(SUMMARY_FIELDS)
        )
        rest_steps = _rest_steps(rest_speed, rest_time, h)
        steps, reason = simulate_kernel(
            np.asarray(state, dtype=np.float64)[:6].copy(),
            np.asarray(wrench, dtype=np.float64),
            n,
            h,
            self.mass,
            self.inertia,
            self.gravity,
            self.friction,
            self.margin,
            self.push_cap,
            self.skip_free,
            self.warm_start,
            y_stop,
            rest_speed,
            rest_steps,
            *self.arrays.contact_scene,
            out,
            traj,
            tele,
            summary,
        )
        return out, steps, reason, traj[: steps + 1], tele[:steps], summary, h

    def propagate(
        self, state: Sequence[float], control: Sequence[float], duration: float
    ) -> tuple[float, ...]:
        """The state after holding the wrench ``control`` for ``duration`` seconds (steps of h;
        stops early, at the last state inside, before a step that would take the centre of mass
        out of the bounds)."""
        out, *_ = self._run(state, control, duration, -np.inf, 0.0, 0.0, record=False)
        out[2] = _wrap_outside(out[2:3])[0]
        return tuple(out.tolist())

    def propagate_path(
        self, state: Sequence[float], control: Sequence[float], duration: float
    ) -> np.ndarray:
        """Every state of :meth:`propagate` (rows, start first; the last row is its result,
        bit for bit): the one compiled run, so the states between are those it visits."""
        _, _, _, traj, *_ = self._run(state, control, duration, -np.inf, 0.0, 0.0, record=True)
        traj[:, 2] = _wrap_outside(traj[:, 2])
        return traj

    def simulate(
        self,
        state: Sequence[float],
        wrench: Sequence[float] = (0.0, 0.0, 0.0),
        duration: float = 10.0,
        y_stop: float = -np.inf,
        rest_speed: float = 0.0,
        rest_time: float = 0.2,
    ) -> Trajectory:
        """Every state of a run of up to ``duration`` s, ending early when the centre of mass
        drops below ``y_stop`` or the part stays slower than ``rest_speed`` (every point,
        length/s) for ``rest_time`` s (Eq. 10's T: the part comes to rest)."""
        if not (math.isfinite(duration) and 0.0 < duration <= 3600.0):
            raise ValueError(f"duration = {duration!r} is outside the allowed range (0, 3600] s")
        _, steps, reason, traj, tele, summary, h = self._run(
            state, wrench, duration, y_stop, rest_speed, rest_time, record=True
        )
        return Trajectory(
            times=np.arange(steps + 1) * h,
            states=traj,
            telemetry=tele,
            summary={k: float(v) for k, v in zip(SUMMARY_FIELDS, summary, strict=True)},
            end=END_REASONS[reason],
            h=h,
            mass=self.mass,
            inertia=self.inertia,
            gravity=(float(self.gravity[0]), float(self.gravity[1])),
            rest_steps=_rest_steps(rest_speed, rest_time, h),
        )
