"""The contract every fidelity level keeps, so planners and experiments treat them alike."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import numpy as np

from feeders.scene import Scene


class Level(Protocol):
    """A model of the part's motion in a scene (paper Eqs. 7-9).

    States are tuples whose first three entries are the pose ``(x, y, yaw)`` of the centre of
    mass; controls are tuples of ``control_dim`` numbers within ``control_bounds()``.
    """

    name: str
    state_dim: int
    control_dim: int
    step: float
    scene: Scene

    def control_bounds(self) -> tuple[np.ndarray, np.ndarray]: ...

    def state_of_pose(self, pose: Sequence[float]) -> tuple[float, ...]:
        """The level's state at rest in ``pose``."""
        ...

    def is_valid(self, state: Sequence[float]) -> bool:
        """Non-penetration (psi_n >= 0) and the bounds."""
        ...

    def clearance(self, state: Sequence[float]) -> float:
        """Smallest signed distance to the obstacles (negative: penetration depth)."""
        ...

    def propagate(
        self, state: Sequence[float], control: Sequence[float], duration: float
    ) -> tuple[float, ...]:
        """The state after applying ``control`` for ``duration`` seconds (the input unchanged)."""
        ...
