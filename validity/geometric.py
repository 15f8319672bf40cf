"""The geometric level (paper Eq. 9): pose increments, non-penetration only.

State: the pose ``q = (x, y, yaw)`` of the part's centre of mass. Input: a pose-increment rate
``u = (vx, vy, omega)`` from the bounded set U. One propagation of duration T takes
``n = ceil(T / h)`` equal steps ``q <- q + (T/n) u`` (each at most h) and stops at the last
pose before a step would penetrate an obstacle or leave the bounds, as Algorithm 1 does
(``break`` on ``Collision``).

As a relaxation of the models above it (issue 21) the level may grant a ``slack`` (length):
a pose is valid when the part penetrates no obstacle deeper than ``slack`` (psi_n >= -slack),
so contact within the dynamic model's overlap and walls made to tolerance are not refused;
:func:`validity.geometric_slack.relaxation_slack` states a design's slack and its parts
(docs/geometric-relaxation.md). ``slack = 0`` is Eq. 9 as the paper writes it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numba import njit

from feeders.scene import Scene
from validity.geometry_kernel import (
    part_penetrates_deeper_than,
    penetrates_deeper_than,
    place_part,
    pose_vertices,
)
from validity.scene_arrays import SceneArrays

DEFAULT_STEP = 0.01  # h (s): with |u| <= 1 a step moves a corner by < 0.03, far below a wall
MAX_SLACK = 0.2  # length: half a wall (0.4 thick); stated slacks are 0.02-0.16 (table3 0.087)


@njit(cache=True)
def _in_bounds(x: float, y: float, bounds: np.ndarray) -> bool:
    return bounds[0] <= x <= bounds[1] and bounds[2] <= y <= bounds[3]


@njit(cache=True)
def _buffers(body, bdiscs):
    """``(single, polygon, placed, world, wdiscs)``: whether the part is one convex polygon
    and no disc (the peg: its polygon ``polygon`` is placed into ``placed`` and checked as it
    is, with no view of a piece per check), and the buffers of a part of several pieces."""
    single = body.shape[0] == 1 and bdiscs.shape[0] == 0
    polygon = np.ascontiguousarray(body[0])
    return single, polygon, np.empty_like(polygon), np.empty_like(body), np.empty_like(bdiscs)


@njit(cache=True)
def _valid_into(
    single,
    polygon,
    placed,
    world,
    wdiscs,
    x,
    y,
    yaw,
    body,
    bcounts,
    bdiscs,
    verts,
    counts,
    aabbs,
    circles,
    bounds,
    ps,
    ds,
):
    """:func:`pose_is_valid` writing the placed part into the caller's buffers (``single``
    to ``wdiscs``: :func:`_buffers`); ``ps (P,)``, ``ds (C,)``: the polygons' and discs'
    slacks."""
    if not _in_bounds(x, y, bounds):
        return False
    if single and bcounts[0] == body.shape[1]:
        pose_vertices(polygon, x, y, yaw, placed)
        return not penetrates_deeper_than(placed, verts, counts, aabbs, circles, ps, ds)
    place_part(body, bcounts, bdiscs, x, y, yaw, world, wdiscs)
    return not part_penetrates_deeper_than(
        world, bcounts, wdiscs, verts, counts, aabbs, circles, ps, ds
    )


@njit(cache=True)
def _slacks(verts, circles, polygon_slack, disc_slack):
    """The polygons' and discs' slacks as given, zeros (Eq. 9 exactly) for one not given."""
    ps = np.zeros(verts.shape[0]) if polygon_slack is None else polygon_slack
    ds = np.zeros(circles.shape[0]) if disc_slack is None else disc_slack
    return ps, ds


@njit(cache=True)
def pose_is_valid(
    x: float,
    y: float,
    yaw: float,
    body,
    bcounts,
    bdiscs,
    verts,
    counts,
    aabbs,
    circles,
    bounds,
    polygon_slack=None,
    disc_slack=None,
):
    """psi_n(q) >= -slack for every obstacle (slacks in length, per polygon ``(P,)`` and disc
    ``(C,)``; None: 0, Eq. 9's psi_n >= 0), and the centre of mass within the bounds. The part:
    convex pieces ``body (Q, K, 2)`` with ``bcounts (Q,)`` vertices and discs ``bdiscs (D, 3)``,
    body frame (:class:`validity.scene_arrays.PartArrays`)."""
    ps, ds = _slacks(verts, circles, polygon_slack, disc_slack)
    single, polygon, placed, world, wdiscs = _buffers(body, bdiscs)
    return _valid_into(
        single,
        polygon,
        placed,
        world,
        wdiscs,
        x,
        y,
        yaw,
        body,
        bcounts,
        bdiscs,
        verts,
        counts,
        aabbs,
        circles,
        bounds,
        ps,
        ds,
    )


@njit(cache=True)
def propagate_increments(
    x,
    y,
    yaw,
    vx,
    vy,
    omega,
    duration,
    h,
    body,
    bcounts,
    bdiscs,
    verts,
    counts,
    aabbs,
    circles,
    bounds,
    polygon_slack=None,
    disc_slack=None,
):
    """Eq. 9 stepped at ``h`` for ``duration``, a step valid when it penetrates no obstacle
    deeper than its slack (as :func:`pose_is_valid`); returns ``(x, y, yaw, steps_taken,
    blocked)``."""
    ps, ds = _slacks(verts, circles, polygon_slack, disc_slack)
    n = max(1, math.ceil(duration / h - 1e-9))
    dt = duration / n
    yaw = (yaw + math.pi) % (2.0 * math.pi) - math.pi
    single, polygon, placed, world, wdiscs = _buffers(body, bdiscs)  # for every step
    for k in range(n):
        nx, ny = x + dt * vx, y + dt * vy
        nyaw = yaw + dt * omega
        nyaw = (nyaw + math.pi) % (2.0 * math.pi) - math.pi
        if not _valid_into(
            single,
            polygon,
            placed,
            world,
            wdiscs,
            nx,
            ny,
            nyaw,
            body,
            bcounts,
            bdiscs,
            verts,
            counts,
            aabbs,
            circles,
            bounds,
            ps,
            ds,
        ):
            return x, y, yaw, k, True
        x, y, yaw = nx, ny, nyaw
    return x, y, yaw, n, False


def _obstacle_slacks(
    slack: float | Sequence[float] | np.ndarray, polygons: int, discs: int
) -> np.ndarray:
    """``slack`` as one value per obstacle ``(polygons + discs,)``, each checked."""
    values = np.array(slack, dtype=np.float64).ravel()
    if values.size == 1:
        values = np.full(polygons + discs, values[0])
    if values.size != polygons + discs:
        raise ValueError(
            f"geometric slack has {values.size} values; the scene has {polygons + discs} "
            f"obstacles ({polygons} polygons, {discs} discs)"
        )
    bad = ~(np.isfinite(values) & (values >= 0.0) & (values <= MAX_SLACK))
    if np.any(bad):
        raise ValueError(
            f"geometric slack = {values[bad][0]!r} is outside the allowed range [0, {MAX_SLACK:g}]"
        )
    return values


class GeometricLevel:
    """Eq. 9 on a scene: validity, clearance and propagation of SE2 poses.

    ``slack`` (length, default 0): the penetration depth a valid pose may have, one number for
    every obstacle or one per obstacle in the scene's order (its polygons, then its discs), as
    :func:`validity.geometric_slack.relaxation_slack` states it (see the module).
    """

    name = "geometric"
    state_dim = 3
    control_dim = 3

    def __init__(
        self,
        scene: Scene,
        step: float = DEFAULT_STEP,
        slack: float | Sequence[float] | np.ndarray = 0.0,
    ):
        if not (math.isfinite(step) and 0.0 < step <= 1.0):
            raise ValueError(f"geometric step h = {step!r} is outside the allowed range (0, 1]")
        self.scene = scene
        self.step = float(step)
        self.arrays = SceneArrays.from_scene(scene)
        a = self.arrays
        self._geometry = a.pose_scene
        self.slack = _obstacle_slacks(slack, a.verts.shape[0], a.circles.shape[0])
        self._slacks = (
            np.ascontiguousarray(self.slack[: a.verts.shape[0]]),
            np.ascontiguousarray(self.slack[a.verts.shape[0] :]),
        )

    def control_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.scene.inputs.bounds()

    def state_of_pose(self, pose: Sequence[float]) -> tuple[float, ...]:
        """The level's state at rest in ``pose`` (here the pose itself)."""
        return (float(pose[0]), float(pose[1]), float(pose[2]))

    def is_valid(self, state: Sequence[float]) -> bool:
        return bool(pose_is_valid(state[0], state[1], state[2], *self._geometry, *self._slacks))

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
            *self._slacks,
        )
        return (x, y, yaw)
