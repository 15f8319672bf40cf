"""The scene's goal region as an OMPL sampleable goal (so RRT's goal bias applies)."""

from __future__ import annotations

import numpy as np
from ompl import base as ob

from feeders.scene import Goal
from planners.spaces import state_codec

YAW_WEIGHT = 0.5  # length units per radian: SE2's own weighting of orientation in OMPL


class GoalBox(ob.GoalSampleableRegion):
    """Centre of mass in the goal box and yaw within tolerance; velocity is free.

    ``distanceGoal`` = distance to the box + ``YAW_WEIGHT`` * yaw excess; 0 inside.
    Goal samples are uniform in the box and the yaw tolerance, drawn from ``rng``.
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
        g = self.goal
        x = self.rng.uniform(g.x_min, g.x_max)
        y = self.rng.uniform(g.y_min, g.y_max)
        yaw = g.yaw + self.rng.uniform(-g.yaw_tol, g.yaw_tol)
        self.write(state, (x, y, yaw, 0.0, 0.0, 0.0)[: self.state_dim])

    def maxSampleCount(self) -> int:
        return 2**31 - 1
