"""The part: a rectangular peg whose centre of mass sits off the middle, toward its heavy end.

The body frame has its origin at the centre of mass and its x axis along the peg, pointing
from the light end to the heavy end; a pose ``(x, y, yaw)`` places that frame in the plane, so
"heavy end down" is ``yaw = -pi/2``.

Default dimensions (length 1.6, width 1) make the paper's designs physical: the peg slides in
the input chute (width ``a`` in [1.1, 1.2]) and the exit chute (``b`` in [1.1, 1.3]) with
0.1-0.3 clearance, and cannot turn round inside either, because turning end for end in a strip
needs the strip to be at least as wide as the peg is long (1.6 > 1.3). The paper gives no
dimensions; among lengths 1.6, 1.7 and 2.0, 1.6 is the one with which the geometric level
reproduces all eleven of the paper's feasibility verdicts (docs/feeder-geometry.md).

The peg is modelled as two uniform halves of different density, heavy half of mass
``heavy_fraction * mass``, which fixes both the centre-of-mass offset and the moment of inertia.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

LENGTH_RANGE = (1e-3, 100.0)  # length and width of a part (the paper's length units)
MASS_RANGE = (1e-9, 1e9)


class PartError(ValueError):
    """A part value is outside its allowed range."""


def _check(name: str, value: float, low: float, high: float) -> float:
    value = float(value)
    if not math.isfinite(value) or not low <= value <= high:
        raise PartError(
            f"part '{name}' = {value!r} is outside the allowed range [{low:g}, {high:g}]"
        )
    return value


@dataclass(frozen=True)
class Peg:
    """A rectangular peg of ``length`` x ``width``, ``mass`` and a heavy end.

    ``com_offset`` is the distance from the geometric centre to the centre of mass, along the
    axis toward the heavy end; ``inertia`` is the moment of inertia about the centre of mass
    (mass * length^2).
    """

    length: float = 1.6
    width: float = 1.0
    mass: float = 1.0
    com_offset: float = 0.2
    inertia: float = 77.0 / 300.0  # Peg.two_density() defaults

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", _check("length", self.length, *LENGTH_RANGE))
        object.__setattr__(self, "width", _check("width", self.width, LENGTH_RANGE[0], self.length))
        object.__setattr__(self, "mass", _check("mass", self.mass, *MASS_RANGE))
        object.__setattr__(
            self, "com_offset", _check("com_offset", self.com_offset, 0.0, self.length / 2)
        )
        object.__setattr__(self, "inertia", _check("inertia", self.inertia, 1e-12, 1e12))

    @classmethod
    def two_density(
        cls,
        length: float = 1.6,
        width: float = 1.0,
        mass: float = 1.0,
        heavy_fraction: float = 0.75,
    ) -> Peg:
        """A peg made of two uniform halves; the heavy half has ``heavy_fraction`` of the mass.

        Centre of mass offset: (m_h - m_l)/m * L/4. Inertia: each half is a (L/2 x w) plate,
        I = m_i ((L/2)^2 + w^2)/12 about its centre, moved to the centre of mass.
        """
        _check("heavy_fraction", heavy_fraction, 0.5, 1.0)
        length = _check("length", length, *LENGTH_RANGE)
        width = _check("width", width, LENGTH_RANGE[0], length)
        mass = _check("mass", mass, *MASS_RANGE)
        m_h, m_l = heavy_fraction * mass, (1.0 - heavy_fraction) * mass
        offset = (m_h - m_l) / mass * length / 4.0
        half = length / 2.0
        own = (half**2 + width**2) / 12.0
        inertia = (
            (m_h + m_l) * own + m_h * (length / 4 - offset) ** 2 + m_l * (length / 4 + offset) ** 2
        )
        return cls(length=length, width=width, mass=mass, com_offset=offset, inertia=inertia)

    def body_vertices(self) -> np.ndarray:
        """Corners in the body frame (origin at the centre of mass), counter-clockwise, (4, 2)."""
        hx, hy, c = self.length / 2.0, self.width / 2.0, self.com_offset
        return np.array([[-hx - c, -hy], [hx - c, -hy], [hx - c, hy], [-hx - c, hy]])

    def bounding_radius(self) -> float:
        """Largest distance from the centre of mass to a corner."""
        return float(np.max(np.hypot(*self.body_vertices().T)))


DEFAULT_PEG = Peg.two_density()
