"""Projections for KPIECE1 and EST: the position of the centre of mass.

OMPL's C++ projections are used so no Python runs per projection: SE2's default projection
(x, y) for pose states, and the same through ``SubspaceProjectionEvaluator`` for SE2 x R^3.
Their cells are 1/20 of the bounds' extent per axis (OMPL's inferred default).
"""

from __future__ import annotations

from ompl import base as ob


def register_position_projection(space: ob.StateSpace, state_dim: int) -> None:
    """Make (x, y) of the centre of mass the default projection of ``space``."""
    if state_dim == 3:
        return  # SE2StateSpace registers (x, y) itself
    space.registerDefaultProjection(ob.SubspaceProjectionEvaluator(space, 0))
