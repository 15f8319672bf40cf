"""Where a passive drop ends: the outcome classes of the orientation transition matrix.

The feeder literature reports a selector by what comes out for what goes in (entry
orientation -> outcome; its efficiency is parts out correctly oriented / parts in). A drop
ends (paper Eq. 10's T) when the centre of mass falls below the goal's top, when the part comes
to rest, when it leaves the bounds, or at t_max; the class says which, and for a part that
stopped, where in the feeder (Fig. 1's landmarks: input chute A, pin B, lip g, funnel, exit
chute C). Free-form scenes without a design get the classes that need no landmarks.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from feeders.scene import Scene

HEAVY_DOWN = "heavy end down"
SIMULATION_FAULT = "ended inside a wall"
OUTCOMES = (
    HEAVY_DOWN,  # in the goal: exits heavy end down (success)
    "heavy end up",  # fell into the exit chute the wrong way round
    "jammed in the exit chute",  # stopped in C above the goal
    "wedged across the funnel",  # stopped in the chamfer above C
    "caught on the pin",  # stopped on or against B
    "wedged at the lip",  # stopped tipping over the lip g
    "stuck in the input chute",  # never left A
    "stopped in the cavity",  # at rest anywhere else inside
    "still moving at t_max",  # neither out nor at rest when the time ran out
    "left the bounds",  # the centre of mass left the scene's bounds
    "ended inside a wall",  # a simulation fault (final-clearance guard), not the design's
)
"""Every class, success first (the order of the transition matrix's columns)."""


def classify(scene: Scene, end: str, pose: Sequence[float], success: bool) -> str:
    """The outcome of a drop that ended with ``end`` (validity.dynamic.END_REASONS) at ``pose``
    (q(T): x, y, yaw)."""
    if success:
        return HEAVY_DOWN
    if end == "inside_wall":
        return SIMULATION_FAULT
    if end == "left_bounds":
        return "left the bounds"
    if end == "crossed":
        return "heavy end up"
    if end == "duration":
        return "still moving at t_max"
    design = scene.design
    if design is None:
        return "stopped in the cavity"
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
    return "stopped in the cavity"
