"""The kinematic level (paper Eq. 8, Algorithm 2): velocity inputs, impulses at collisions.

State: pose and velocity ``(x, y, yaw, vx, vy, omega)`` of the part's centre of mass; the
velocity is the one the part had at the end of the last step (after any impact). Input: a
velocity ``u = (vx, vy, omega)`` from the scene's bounded set U (``inputs.max_speed``,
``inputs.max_turn``). Each step of h the part moves with ``v = u``; a collision stops the
motion at the time of impact, the impact law (Routh's method with Coulomb friction
``scene.friction`` and Stronge's restitution ``scene.restitution``,
:mod:`validity.impact`) changes the velocity by ``M^-1 Imp``, and the part goes on with it
for the rest of the step (:mod:`validity.impulse_stepper`). Non-penetration is exact:
psi_n(q) >= 0 after every step, and no wall is tunnelled at any speed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from feeders.scene import Scene
from validity.impulse_stepper import (
    END_REASONS,
    SUMMARY_FIELDS,
    TELEMETRY_COLUMNS,
    kinematic_kernel,
)
from validity.moving_part import MovingPartLevel, check_ranges, run_buffers

DEFAULT_STEP = 0.01  # h (s), as the geometric level: the impacts make the result exact in h
CONTACT_BAND = 1e-4  # gap (length) at which the part touches; advances stop at half of it
MAX_IMPACTS = 32  # sequential impacts per collision before the part is stopped (a jam)


@dataclass(frozen=True)
class KinematicRun:
    """One propagation: states (rows x, y, yaw, vx, vy, omega, start first), per-step
    telemetry (columns ``TELEMETRY_COLUMNS``), totals (``SUMMARY_FIELDS``) and why it ended."""

    states: np.ndarray = field(repr=False)
    telemetry: np.ndarray = field(repr=False)
    summary: dict
    end: str
    h: float

    @property
    def final(self) -> np.ndarray:
        return self.states[-1]


class KinematicLevel(MovingPartLevel):
    """Eq. 8 with Algorithm 2's impacts on a scene: validity, clearance and propagation."""

    name = "kinematic"
    penetration_tolerance = 0.0  # psi_n(q) >= 0 exactly

    def __init__(
        self,
        scene: Scene,
        step: float = DEFAULT_STEP,
        contact_band: float = CONTACT_BAND,
        max_impacts: int = MAX_IMPACTS,
    ):
        check_ranges(
            "kinematic",
            (("step h", step, 1e-6, 1.0), ("contact band", contact_band, 1e-9, 0.01)),
        )
        if not isinstance(max_impacts, int):
            raise ValueError(f"kinematic max_impacts = {max_impacts!r} must be an integer")
        check_ranges("kinematic", (("max_impacts", max_impacts, 1, 10_000),))
        super().__init__(scene)
        self.step = float(step)
        self.contact_band = float(contact_band)
        self.max_impacts = int(max_impacts)
        self.restitution = float(scene.restitution)
        # Largest |vx|, |vy| or |omega| a propagated state can have: impacts never add kinetic
        # energy, so no component exceeds what U's fastest input carries, sqrt(2 E_max / m) or
        # sqrt(2 E_max / I) (length/s, rad/s).
        s, w = scene.inputs.max_speed, scene.inputs.max_turn
        energy2 = self.mass * 2.0 * s * s + self.inertia * w * w  # 2 E_max
        self.velocity_limit = math.sqrt(energy2 / min(self.mass, self.inertia)) * (1.0 + 1e-9)

    def control_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.scene.inputs.bounds()

    def _compiled_run(
        self, state: Sequence[float], control: Sequence[float], duration: float, record: bool
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, int, int, float]:
        """The kernel's run: ``(out, traj, tele, summary, steps, reason, h)``."""
        n, h = self.steps_of(duration)
        out, traj, tele, summary = run_buffers(
            n, record, len(TELEMETRY_COLUMNS), len(SUMMARY_FIELDS)
        )
        steps, reason = kinematic_kernel(
            np.array(state[:6], dtype=np.float64),
            np.array(control[:3], dtype=np.float64),
            n,
            h,
            self.mass,
            self.inertia,
            self.friction,
            self.restitution,
            self.contact_band,
            self.max_impacts,
            *self.arrays.contact_scene,
            out,
            traj,
            tele,
            summary,
        )
        return out, traj, tele, summary, steps, reason, h

    def run(
        self, state: Sequence[float], control: Sequence[float], duration: float, record: bool
    ) -> KinematicRun:
        """Propagate and, with ``record``, keep every state and the per-step telemetry."""
        out, traj, tele, summary, steps, reason, h = self._compiled_run(
            state, control, duration, record
        )
        return KinematicRun(
            states=traj[: steps + 1] if record else out[None, :],
            telemetry=tele[:steps],
            summary={k: float(v) for k, v in zip(SUMMARY_FIELDS, summary, strict=True)},
            end=END_REASONS[reason],
            h=h,
        )

    def propagate(
        self, state: Sequence[float], control: Sequence[float], duration: float
    ) -> tuple[float, ...]:
        """The state after commanding the velocity ``control`` for ``duration`` seconds (steps
        of at most h; stops before a step that would take the centre of mass out of bounds)."""
        out, *_ = self._compiled_run(state, control, duration, record=False)
        return tuple(out.tolist())  # no telemetry to pack: OMPL calls this for every step

    def propagate_path(
        self, state: Sequence[float], control: Sequence[float], duration: float
    ) -> np.ndarray:
        """Every state of :meth:`propagate` (rows, start first; the last row is its result)."""
        _, traj, _, _, steps, _, _ = self._compiled_run(state, control, duration, record=True)
        return traj[: steps + 1]
