"""The geometric level (paper Eq. 9): pose increments, non-penetration only.

State: the pose ``q = (x, y, yaw)`` of the part's centre of mass. Input: a pose-increment rate
``u = (vx, vy, omega)`` from the bounded set U. One propagation of duration T takes
``n = ceil(T / h)`` equal steps ``q <- q + (T/n) u`` (each at most h) and stops at the last
pose before a step would penetrate an obstacle or leave the bounds, as Algorithm 1 does
(``break`` on ``Collision``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numba import njit

from feeders.scene import Scene
from validity.geometry_kernel import penetrates, pose_vertices
from validity.scene_arrays import SceneArrays

DEFAULT_STEP = 0.01  # h (s): with |u| <= 1 a step moves a corner by < 0.03, far below a wall


@njit(cache=True)
def _in_bounds(x: float, y: float, bounds: np.ndarray) -> bool:
    return bounds[0] <= x <= bounds[1] and bounds[2] <= y <= bounds[3]


@njit(cache=True)
def _valid_into(world, x, y, yaw, body, verts, counts, aabbs, circles, bounds):
    """:func:`pose_is_valid` writing the placed corners into the caller's buffer ``world``."""
    if not _in_bounds(x, y, bounds):
        return False
    pose_vertices(body, x, y, yaw, world)
    return not penetrates(world, verts, counts, aabbs, circles)


@njit(cache=True)
def pose_is_valid(x: float, y: float, yaw: float, body, verts, counts, aabbs, circles, bounds):
    """psi_n(q) >= 0 for every obstacle, and the centre of mass within the bounds."""
    world = np.empty_like(body)
    return _valid_into(world, x, y, yaw, body, verts, counts, aabbs, circles, bounds)


@njit(cache=True)
def propagate_increments(
    x, y, yaw, vx, vy, omega, duration, h, body, verts, counts, aabbs, circles, bounds
):
    """Eq. 9 stepped at ``h`` for ``duration``; returns ``(x, y, yaw, steps_taken, blocked)``."""
    n = max(1, math.ceil(duration / h - 1e-9))
    dt = duration / n
    yaw = (yaw + math.pi) % (2.0 * math.pi) - math.pi
    world = np.empty_like(body)  # one buffer for every step of this propagation
    for k in range(n):
        nx, ny = x + dt * vx, y + dt * vy
        nyaw = yaw + dt * omega
        nyaw = (nyaw + math.pi) % (2.0 * math.pi) - math.pi
        if not _valid_into(world, nx, ny, nyaw, body, verts, counts, aabbs, circles, bounds):
            return x, y, yaw, k, True
        x, y, yaw = nx, ny, nyaw
    return x, y, yaw, n, False


class GeometricLevel:
    """Eq. 9 on a scene: validity, clearance and propagation of SE2 poses."""

    name = "geometric"
    state_dim = 3
    control_dim = 3

    def __init__(self, scene: Scene, step: float = DEFAULT_STEP):
        if not (math.isfinite(step) and 0.0 < step <= 1.0):
            raise ValueError(f"geometric step h = {step!r} is outside the allowed range (0, 1]")
        self.scene = scene
        self.step = float(step)
        self.arrays = SceneArrays.from_scene(scene)
        a = self.arrays
        self._geometry = (a.body, a.verts, a.counts, a.aabbs, a.circles)

    def control_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.scene.inputs.bounds()

    def state_of_pose(self, pose: Sequence[float]) -> tuple[float, ...]:
        """The level's state at rest in ``pose`` (here the pose itself)."""
        return (float(pose[0]), float(pose[1]), float(pose[2]))

    def is_valid(self, state: Sequence[float]) -> bool:
        return bool(
            pose_is_valid(state[0], state[1], state[2], *self._geometry, self.arrays.bounds)
        )

    def clearance(self, state: Sequence[float]) -> float:
        """Smallest signed distance to an obstacle (negative: penetration depth)."""
        return self.arrays.clearance(state[0], state[1], state[2])

    def propagate(
        self, state: Sequence[float], control: Sequence[float], duration: float
    ) -> tuple[float, float, float]:
        x, y, yaw, _, _ = propagate_increments(
            state[0],
            state[1],
            state[2],
            control[0],
            control[1],
            control[2],
            duration,
            self.step,
            *self._geometry,
            self.arrays.bounds,
        )
        return (x, y, yaw)
