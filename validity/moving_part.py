"""What the kinematic and dynamic levels share: a part whose state is pose and velocity.

State ``(x, y, yaw, vx, vy, omega)`` of the centre of mass on SE2 x R^3, three inputs, the
scene as kernel arrays, and validity as bounds, a speed limit and a penetration tolerance.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from feeders.scene import Scene
from validity.scene_arrays import SceneArrays


def check_ranges(level: str, options: Sequence[tuple[str, float, float, float]]) -> None:
    """Raise a ValueError naming the level, the option and its allowed range for the first
    ``(label, value, low, high)`` whose value is not a finite number in [low, high]."""
    for label, value, low, high in options:
        if not (math.isfinite(value) and low <= value <= high):
            raise ValueError(
                f"{level} {label} = {value!r} is outside the allowed range [{low}, {high}]"
            )


class MovingPartLevel:
    """Base of the levels whose state carries a velocity (Eqs. 7 and 8)."""

    state_dim = 6
    control_dim = 3
    velocity_limit: float
    penetration_tolerance: float
    step: float

    def __init__(self, scene: Scene):
        self.scene = scene
        self.arrays = SceneArrays.from_scene(scene)
        self.mass, self.inertia = scene.part.mass, scene.part.inertia
        self.friction = float(scene.friction)

    def state_of_pose(self, pose: Sequence[float]) -> tuple[float, ...]:
        """The part at rest in ``pose``."""
        return (float(pose[0]), float(pose[1]), float(pose[2]), 0.0, 0.0, 0.0)

    def clearance(self, state: Sequence[float]) -> float:
        """Smallest signed distance to the obstacles (negative: penetration depth)."""
        return self.arrays.clearance(state[0], state[1], state[2])

    def is_valid(self, state: Sequence[float]) -> bool:
        """Centre of mass in bounds, speeds within ``velocity_limit`` and no overlap deeper
        than ``penetration_tolerance``."""
        return self.arrays.moving_state_is_valid(
            state, self.velocity_limit, self.penetration_tolerance
        )

    def steps_of(self, duration: float) -> tuple[int, float]:
        """``(n, h)``: n equal steps of at most the level's step that make exactly
        ``duration`` (so a propagation continued from its own result repeats the same
        arithmetic)."""
        n = max(1, math.ceil(duration / self.step - 1e-9))
        return n, duration / n


MAX_RECORDED_STEPS = 10_000_000  # states and telemetry of a recorded run: about 1 GB


def run_buffers(
    n_steps: int, record: bool, telemetry_columns: int, summary_fields: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(out (6,), traj, tele, summary)`` for a compiled run of ``n_steps``: ``traj (n + 1, 6)``
    and ``tele (n, telemetry_columns)`` only when ``record`` (empty otherwise, which tells the
    kernel not to record), ``summary`` zeroed. A recording of more than
    ``MAX_RECORDED_STEPS`` steps (13 numbers a step: about 1 GB at the bound) raises
    ValueError before anything is allocated."""
    if record and n_steps > MAX_RECORDED_STEPS:
        raise ValueError(
            f"a recorded run of {n_steps} steps; at most {MAX_RECORDED_STEPS} are recorded "
            "(duration / h): a shorter duration or a larger step"
        )
    rows = n_steps if record else 0
    return (
        np.empty(6),
        np.empty((rows + 1 if record else 0, 6)),
        np.empty((rows, telemetry_columns)),
        np.zeros(summary_fields),
    )
