"""The passive drop's end rule and outcome, on the states of any engine.

partfeeder's compiled loop (:func:`validity.stewart_trinkle.simulate_kernel`, called by
:func:`experiments.drop.passive.passive_drop`) ends a drop after the step where, in this
order: the centre of mass is below the goal target's y (``crossed``, Eq. 10's T); the centre
of mass is out of the scene's bounds (``left_bounds``: that step is not taken, the drop ends at
the state before); every point of the part has been slower than ``REST_SPEED`` (|v| + R|omega|,
R the part's bounding radius) for ``REST_TIME`` (``at_rest``: q(T) is where the still window
began); else at ``t_max`` (``duration``). The peers are stepped in chunks and the same rule is
found in each chunk's states here, vectorised, so every engine's drop ends by the same rule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from experiments.drop.outcomes import classify
from experiments.drop.passive import REST_SPEED, REST_TIME
from feeders.scene import Scene, wrap_angle


def rest_steps(h: float) -> int:
    """Steps of stillness that end a drop at rest at step ``h`` (s)."""
    return math.ceil(REST_TIME / h)


@dataclass
class EndRule:
    """The end rule of one drop (``y_stop`` the goal target's y, ``bounds`` the scene's,
    ``radius`` the part's bounding radius, ``rest`` steps of stillness), with the stillness
    count carried from one chunk of states to the next."""

    y_stop: float
    bounds: tuple[float, float, float, float]
    radius: float
    rest: int
    still: int = 0

    @classmethod
    def of(cls, scene: Scene, h: float) -> EndRule:
        return cls(
            float(scene.goal.target[1]),
            tuple(float(b) for b in scene.bounds),  # type: ignore[arg-type]
            scene.part.bounding_radius(),
            rest_steps(h),
        )

    def first_end(self, chunk: np.ndarray) -> tuple[int, str] | None:
        """The first row of ``chunk`` (states after consecutive steps) that ends the drop and
        why ("crossed", "left_bounds", "at_rest"), or None (the stillness count goes on)."""
        x, y = chunk[:, 0], chunk[:, 1]
        speed = np.hypot(chunk[:, 3], chunk[:, 4]) + self.radius * np.abs(chunk[:, 5])
        index = np.arange(len(chunk))
        moving = np.where(speed < REST_SPEED, -1, index)
        last_moving = np.maximum.accumulate(moving)
        still = np.where(last_moving < 0, self.still + index + 1, index - last_moving)
        crossed = y < self.y_stop
        x0, x1, y0, y1 = self.bounds
        out = ~((x0 <= x) & (x <= x1) & (y0 <= y) & (y <= y1))
        rest = still >= self.rest if self.rest > 0 else np.zeros(len(chunk), dtype=bool)
        ends = np.flatnonzero(crossed | out | rest)
        if len(ends) == 0:
            self.still = int(still[-1]) if len(chunk) else self.still
            return None
        k = int(ends[0])
        reason = "crossed" if crossed[k] else "left_bounds" if out[k] else "at_rest"
        return k, reason


@dataclass(frozen=True)
class Ending:
    """Where and how a drop ended: q(T) (x, y, wrapped yaw), T (s), the end reason, success
    (q(T) in the goal) and the outcome class (:mod:`experiments.drop.outcomes`)."""

    end: str
    T: float
    pose: tuple[float, float, float]
    success: bool
    outcome: str


def ending_of(
    scene: Scene, end: str, settle_state: np.ndarray, T: float, success: bool | None = None
) -> Ending:
    """The drop's ending from its end reason and the state at T; ``success`` defaults to q(T)
    in the goal (partfeeder's drop passes its own, which its final-clearance guard may deny)."""
    pose = (float(settle_state[0]), float(settle_state[1]), wrap_angle(float(settle_state[2])))
    if success is None:
        success = scene.goal.contains(pose)
    return Ending(end, float(T), pose, success, classify(scene, end, pose, success))
