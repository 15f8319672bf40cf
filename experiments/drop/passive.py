"""The passive drop of the part through a scene with the dynamic level (paper Section 4, Eq. 10).

The part starts at rest in an entry pose and falls under gravity, with no input. The run ends
at Eq. 10's T: when the centre of mass drops below the goal target's height (q_goal, the top
of the goal box), or when the part comes to rest, or at ``t_max``. The drop succeeds when the
pose at T is in the goal region: for the feeder, inside the exit chute with the heavy end down.

A drop that ends with the part inside a wall deeper than the level's penetration tolerance
(the final-clearance guard, measured by the separating-axis signed distance of
:mod:`validity.geometry_kernel`, which sees a part straddling a thin wall) is a fault of the
simulation, not an outcome: it ends ``inside_wall`` and never counts as a success.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from feeders.scene import Scene, wrap_angle
from validity.dynamic import DEFAULT_STEP, DynamicLevel, Trajectory

REST_SPEED = 1e-3  # every point of the part slower than this (length/s) ...
REST_TIME = 0.2  # ... for this long (s) counts as at rest
PAPER_WEIGHT = 5.0  # w of Eq. 10 in the paper
INSIDE_WALL = "inside_wall"  # a drop's end: q(T) overlaps a wall beyond the tolerance


@dataclass(frozen=True)
class DropResult:
    """One passive drop: the verdict, Eq. 10's T and distance to q_goal, and the health of the
    simulation (deepest overlap, energy rise, LCP failures). Plain data."""

    scene: str
    orientation: str
    success: bool
    end: str
    T: float
    final_pose: tuple[float, float, float]
    goal_error: float
    max_penetration: float
    energy_rise: float
    energy_change: float
    lcp_solves: int
    lcp_failures: int
    regularised: int
    frictionless_fallbacks: int
    steps: int
    contact_searches: int
    wall_time: float
    trajectory: Trajectory = field(repr=False)
    final_depth: float = 0.0  # overlap of the part with the walls at q(T) (length; 0: clear)

    def summary(self) -> dict:
        return {
            "scene": self.scene,
            "orientation": self.orientation,
            "success": self.success,
            "end": self.end,
            "T_s": round(self.T, 6),
            "final_pose": [round(v, 6) for v in self.final_pose],
            "goal_error": round(self.goal_error, 6),
            "max_penetration": self.max_penetration,
            "energy_rise": self.energy_rise,
            "energy_change": round(self.energy_change, 9),
            "lcp_solves": self.lcp_solves,
            "lcp_failures": self.lcp_failures,
            "regularised": self.regularised,
            "frictionless_fallbacks": self.frictionless_fallbacks,
            "steps": self.steps,
            "contact_searches": self.contact_searches,
            "wall_time_s": round(self.wall_time, 6),
            "final_depth": self.final_depth,
        }


def goal_error(scene: Scene, pose: Sequence[float]) -> float:
    """||q(T) - q_goal|| of Eq. 10 (position and wrapped yaw difference, Euclidean)."""
    gx, gy, gyaw = scene.goal.target
    return math.sqrt((pose[0] - gx) ** 2 + (pose[1] - gy) ** 2 + wrap_angle(pose[2] - gyaw) ** 2)


def passive_drop(
    scene: Scene,
    orientation: str,
    step: float = DEFAULT_STEP,
    t_max: float = 10.0,
    level: DynamicLevel | None = None,
    start: Sequence[float] | None = None,
) -> DropResult:
    """Drop the part from the scene's start ``orientation`` and judge where it ends; ``start``
    (x, y, yaw, vx, vy, omega) replaces the start at rest in that orientation's pose."""
    level = level or DynamicLevel(scene, step=step)
    if start is None:
        start = level.state_of_pose(scene.start(orientation))
    level.simulate(start, duration=level.step)  # load the compiled kernel before the clock
    t0 = time.perf_counter()
    run = level.simulate(
        start,
        duration=t_max,
        y_stop=scene.goal.target[1],
        rest_speed=REST_SPEED,
        rest_time=REST_TIME,
    )
    wall = time.perf_counter() - t0
    final = run.states[run.settle_index]  # q(T): where it came to rest, or the end
    pose = (float(final[0]), float(final[1]), wrap_angle(float(final[2])))
    depth = max(0.0, -level.clearance(final))
    inside = depth > level.penetration_tolerance
    energy = run.energy()
    s = run.summary
    return DropResult(
        scene=scene.name,
        orientation=orientation,
        success=scene.goal.contains(pose) and not inside,
        end=INSIDE_WALL if inside else run.end,
        T=float(run.times[run.settle_index]),
        final_pose=pose,
        goal_error=goal_error(scene, pose),
        max_penetration=s["max_penetration"],
        energy_rise=run.energy_rise(),
        energy_change=float(energy[-1] - energy[0]),
        lcp_solves=int(s["lcp_solves"]),
        lcp_failures=int(s["failures"]),
        regularised=int(s["regularised"]),
        frictionless_fallbacks=int(s["frictionless_fallbacks"]),
        steps=int(s["steps"]),
        contact_searches=int(s["contact_searches"]),
        wall_time=wall,
        trajectory=run,
        final_depth=depth,
    )


def eq10_objective(results: Sequence[DropResult], weight: float = PAPER_WEIGHT) -> float:
    """G = sum_i w ||q_i(T_i) - q_goal|| + T_i over the entry orientations (paper Eq. 10)."""
    return float(np.sum([weight * r.goal_error + r.T for r in results]))
