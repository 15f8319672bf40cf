"""The part's speed just past the input chute's lip against the Coulomb sliding closed form.

The input chute (:func:`feeders.feeder.interior_edges`) rises to the right at angle theta from
its lip g (the floor's lower left end), so the part slides down it along -u, u = (cos theta,
sin theta). While the centre of mass is still over the floor, nothing but Coulomb friction acts
along the floor, so the speed along it after the centre of mass has moved a distance s down
the chute is the closed form v = sqrt(v0^2 + 2 g s (sin theta - mu cos theta)), v0 the start's
speed down the chute. The part starts centred across the chute and first falls onto its floor;
the fall gains mu g cos(theta) t more along the floor than sliding would, and a plastic landing
with Coulomb friction takes the same mu v_n = mu g cos(theta) t away, so the closed form holds
from the start (up to the small yaw of the entry).

The measurement point (issue 26's slab scene, where the phantom contact at a convex corner
took the speed away): the first state whose centre of mass is ``PAST_LIP`` before the lip along
the chute. By then the leading end (0.66 ahead of the centre of mass heavy end first, 1.54
heavy end last, for the default peg) has passed the lip, and the part has not begun to tip.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from feeders.scene import Scene

PAST_LIP = 0.2  # the centre of mass this far (length) before the lip, along the chute
SLOW = 0.9  # a drop whose ratio is below this lost speed at the lip


@dataclass(frozen=True)
class LipSpeed:
    """Measured speed (length/s) of the centre of mass at the measurement point, the closed
    form's speed there, their ratio, and the distance s (length) slid from the start."""

    speed: float
    reference: float
    ratio: float
    distance: float


def along_chute(scene: Scene, xy: np.ndarray) -> np.ndarray:
    """Distance (length) of points (n, 2) from the lip along the input chute (up is +)."""
    design = scene.design
    if design is None:
        raise ValueError(f"scene {scene.name} has no design: no input chute, no lip")
    u = np.array([math.cos(design.theta), math.sin(design.theta)])
    return (np.asarray(xy) - np.array([design.gx, design.gy])) @ u


def closed_form_speed(scene: Scene, start: Sequence[float], distance: float) -> float:
    """Coulomb sliding speed (length/s) after the centre of mass slid ``distance`` down the
    chute from ``start`` (x, y, yaw, vx, vy, omega), at the scene's mu and gravity."""
    design = scene.design
    assert design is not None
    g = math.hypot(*scene.gravity)
    theta, mu = design.theta, scene.friction
    v0 = -(start[3] * math.cos(theta) + start[4] * math.sin(theta))
    return math.sqrt(
        max(0.0, v0 * v0 + 2.0 * g * distance * (math.sin(theta) - mu * math.cos(theta)))
    )


def lip_speed(scene: Scene, start: Sequence[float], states: np.ndarray) -> LipSpeed | None:
    """The part's speed just past the lip in a drop's ``states`` (rows x, y, yaw, vx, vy,
    omega, the start first) against the closed form; None when the centre of mass never gets
    within ``PAST_LIP`` of the lip (stuck in the chute) or starts there, and for a scene with
    no 12-parameter design (a device family's: its lip is not named, issue 35)."""
    if scene.design is None:
        return None
    along = along_chute(scene, states[:, :2])
    if along[0] <= PAST_LIP:
        return None
    reached = np.flatnonzero(along <= PAST_LIP)
    if len(reached) == 0:
        return None
    k = int(reached[0])
    distance = float(along[0] - along[k])
    speed = float(math.hypot(states[k, 3], states[k, 4]))
    reference = closed_form_speed(scene, start, distance)
    ratio = speed / reference if reference > 0 else math.nan
    return LipSpeed(speed, reference, ratio, distance)
