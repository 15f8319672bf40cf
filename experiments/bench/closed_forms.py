"""Closed forms the work-precision benchmarks measure errors against (no simulation here).

A rigid box under gravity g (length/s^2, pointing down) with Coulomb friction mu:

* on an incline at angle ``slope`` (rad), from rest: it slides when mu < tan(slope), with
  constant acceleration g (sin slope - mu cos slope) along the slope; else it sticks
  (displacement 0 for all t);
* in free flight: the centre of mass follows a parabola, the yaw turns at a constant rate;
* dropped flat from rest with a gap above a floor, without restitution: it lands at
  t* = sqrt(2 gap / g) and stays there.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


def incline_displacement(mu: float, slope: float, g: float, t: float) -> float:
    """Distance (length) slid down an incline at ``slope`` rad in ``t`` s from rest (0 when
    the box sticks, mu >= tan slope)."""
    a = g * (math.sin(slope) - mu * math.cos(slope))
    return 0.5 * a * t * t if a > 0.0 else 0.0


def ballistic_state(start: Sequence[float], gravity: Sequence[float], t: float) -> np.ndarray:
    """State (x, y, yaw, vx, vy, omega) at ``t`` s of a free body from ``start`` under the
    ``gravity`` vector (no contact, no drag)."""
    x, y, yaw, vx, vy, omega = (float(v) for v in start)
    gx, gy = float(gravity[0]), float(gravity[1])
    return np.array(
        [
            x + vx * t + 0.5 * gx * t * t,
            y + vy * t + 0.5 * gy * t * t,
            yaw + omega * t,
            vx + gx * t,
            vy + gy * t,
            omega,
        ]
    )


def landing_time(gap: float, g: float) -> float:
    """When (s) a body dropped from rest falls through ``gap`` (length) under ``g``."""
    if gap < 0.0 or g <= 0.0:
        raise ValueError(f"need gap >= 0 and g > 0, got gap = {gap!r}, g = {g!r}")
    return math.sqrt(2.0 * gap / g)
