"""The scene's goal region as an OMPL sampleable goal (so RRT's goal bias applies)."""

from __future__ import annotations

import numpy as np
from ompl import base as ob

from feeders.scene import Goal
from planners.spaces import state_codec

YAW_WEIGHT = 0.5  # length units per radian: SE2's own weighting of orientation in OMPL


def goal_sample(goal: Goal, rng: np.random.Generator) -> tuple[float, float, float]:
    """A pose ``(x, y, yaw)`` the goal accepts, uniform in its box and over its acceptable
    yaws: a window chosen in proportion to its width when there are several (issue 24: a goal
    of more than one orientation), then uniform within it."""
    x = rng.uniform(goal.x_min, goal.x_max)
    y = rng.uniform(goal.y_min, goal.y_max)
    centre, tol = goal.yaw, goal.yaw_tol
    if goal.more_yaws:
        widths = np.array([w for _, w in goal.windows])
        centre, tol = goal.windows[rng.choice(len(widths), p=widths / widths.sum())]
    return float(x), float(y), float(centre + rng.uniform(-tol, tol))


class GoalBox(ob.GoalSampleableRegion):
    """Centre of mass in the goal box and yaw within tolerance; velocity is free.

    ``distanceGoal`` = distance to the box + ``YAW_WEIGHT`` * yaw excess; 0 inside.
    Goal samples are :func:`goal_sample`'s, drawn from ``rng``.
    """

    def __init__(
        self, si: ob.SpaceInformation, goal: Goal, state_dim: int, rng: np.random.Generator
    ):
        super().__init__(si)
        self.goal = goal
        self.rng = rng
        self.read, self.write = state_codec(state_dim)
        self.state_dim = state_dim
        self.setThreshold(1e-9)

    def distanceGoal(self, state) -> float:
        x, y, yaw = self.read(state)[:3]
        g = self.goal
        return g.position_gap(x, y) + YAW_WEIGHT * g.yaw_gap(yaw)

    def sampleGoal(self, state) -> None:
        x, y, yaw = goal_sample(self.goal, self.rng)
        self.write(state, (x, y, yaw, 0.0, 0.0, 0.0)[: self.state_dim])

    def maxSampleCount(self) -> int:
        return 2**31 - 1
