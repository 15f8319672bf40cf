"""Where a passive drop ends: the outcome classes of the orientation transition matrix.

The feeder literature reports a selector by what comes out for what goes in (entry
orientation -> outcome; its efficiency is parts out correctly oriented / parts in). A drop
ends (paper Eq. 10's T) when the centre of mass falls below the goal's top, when the part comes
to rest, when it leaves the bounds, or at t_max; the class says which, and for a part that
stopped, where in the feeder (Fig. 1's landmarks: input chute A, pin B, lip g, funnel, exit
chute C). Free-form scenes and device families without a design get the classes that need no
landmarks.

A drop that reached the goal, or fell below its top, is named by the part's orientation
classes (:class:`feeders.scene.OrientationClass`; the peg's "heavy end down" and "heavy end
up" unless the scene names others, as a family's ``orientations:`` does for the cup):

* in the goal: the goal's class (of the classes it accepts, the one its yaw belongs to, else
  the first);
* below the goal's top, not in it: the class of its final yaw; but a yaw whose class the goal
  accepts is :data:`MISSED_GOAL` (right way round, outside the goal's box or its tighter yaw
  tolerance: never counted as a success class), and a yaw in no class's window
  :data:`feeders.scene.OTHER_ORIENTATION`.

For the feeder this is today's "crossed => heavy end up": a peg below the goal's top is within
the exit chute (2.2 long, at most 1.3 wide: it tilts at most 0.27 rad from vertical, inside the
goal's 0.35), so a crossing that is not a success is upside down.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from feeders.scene import HEAVY_END_DOWN, HEAVY_END_UP, Scene

HEAVY_DOWN = HEAVY_END_DOWN  # the feeder's success class
SIMULATION_FAULT = "ended inside a wall"
MISSED_GOAL = "missed the goal"  # below the goal's top in an accepted class, not in the goal
STOPPED = "stopped in the cavity"
LANDMARK_CLASSES = (
    "jammed in the exit chute",  # stopped in C above the goal
    "wedged across the funnel",  # stopped in the chamfer above C
    "caught on the pin",  # stopped on or against B
    "wedged at the lip",  # stopped tipping over the lip g
    "stuck in the input chute",  # never left A
)
"""Where a part stopped in the 12-parameter feeder (Fig. 1's landmarks)."""
FAILURE_CLASSES = (
    STOPPED,  # at rest anywhere else inside
    "still moving at t_max",  # neither out nor at rest when the time ran out
    "left the bounds",  # the centre of mass left the scene's bounds
    SIMULATION_FAULT,  # a simulation fault (final-clearance guard), not the design's
)
"""The failures every scene has, whatever its part."""
OUTCOMES = (HEAVY_DOWN, HEAVY_END_UP, *LANDMARK_CLASSES, *FAILURE_CLASSES)
"""The feeder's classes, success first (the order of the transition matrix's columns)."""


def outcome_classes(scene: Scene) -> tuple[str, ...]:
    """The transition matrix's columns for drops through ``scene``: its orientation classes
    (the goal's first), the feeder's landmarks when it has a design, then
    :data:`FAILURE_CLASSES`. For the feeder: :data:`OUTCOMES`. (:data:`MISSED_GOAL` and
    :data:`feeders.scene.OTHER_ORIENTATION` are columns only when a drop ended so.)"""
    landmarks = LANDMARK_CLASSES if scene.design is not None else ()
    return (*scene.orientation_names, *landmarks, *FAILURE_CLASSES)


def classify(scene: Scene, end: str, pose: Sequence[float], success: bool) -> str:
    """The outcome of a drop that ended with ``end`` (validity.dynamic.END_REASONS) at ``pose``
    (q(T): x, y, yaw), ``success`` when q(T) is in the goal."""
    accepted = scene.goal.orientations
    if success:
        named = scene.orientation_of(float(pose[2]))
        return named if named in accepted else accepted[0]
    if end == "inside_wall":
        return SIMULATION_FAULT
    if end == "left_bounds":
        return "left the bounds"
    if end == "crossed":
        named = scene.orientation_of(float(pose[2]))
        return MISSED_GOAL if named in accepted else named
    if end == "duration":
        return "still moving at t_max"
    design = scene.design
    if design is None:
        return STOPPED
    x, y = float(pose[0]), float(pose[1])
    length = scene.part.length
    if y < 0.0 and abs(x) <= design.b / 2:
        return "jammed in the exit chute"
    if math.hypot(x - design.fx, y - design.fy) <= design.r + 0.5 * length:
        return "caught on the pin"
    ux, uy = math.cos(design.theta), math.sin(design.theta)
    along = (x - design.gx) * ux + (y - design.gy) * uy
    across = -(x - design.gx) * uy + (y - design.gy) * ux
    if 0.0 <= across <= design.a and along > 0.5 * length:
        return "stuck in the input chute"
    if math.hypot(x - design.gx, y - design.gy) <= 0.75 * length:
        return "wedged at the lip"
    if y <= design.c + 0.5 * length:
        return "wedged across the funnel"
    return STOPPED
