"""Projections for KPIECE1 and EST.

For pose-and-velocity states (the kinematic and dynamic levels) the projection is the pose
``(x, y, yaw)`` of the centre of mass: the feeder's problem is turning the part, and a
projection onto position alone counts a cell as explored once the part has been there in any
orientation, so KPIECE1 stops pushing toward new orientations (measured on table3, kinematic
level, 10 s budget: 8 of 12 seeded runs solved with (x, y), 16 of 16 with (x, y, yaw)). Its
cells are OMPL's inferred default, 1/20 of each projected extent. SE2 states keep OMPL's own
(x, y) projection (C++, no Python per call), as the geometric level was calibrated with it.
"""

from __future__ import annotations

from ompl import base as ob


class PoseProjection(ob.ProjectionEvaluator):
    """``(x, y, yaw)`` of the SE2 pose that is the first subspace of a compound state."""

    def __init__(self, space: ob.StateSpace):
        super().__init__(space)

    def getDimension(self) -> int:
        return 3

    def project(self, state, out) -> None:
        pose = state[0]
        out[0], out[1], out[2] = pose.getX(), pose.getY(), pose.getYaw()


def register_pose_projection(space: ob.StateSpace, state_dim: int) -> None:
    """Make the part's pose the default projection of ``space`` (see the module docstring)."""
    if state_dim == 3:
        return  # SE2StateSpace registers (x, y) itself
    space.registerDefaultProjection(PoseProjection(space))
