"""The part: a rectangular peg whose centre of mass sits off the middle, toward its heavy end.

The body frame has its origin at the centre of mass and its x axis along the peg, pointing
from the light end to the heavy end; a pose ``(x, y, yaw)`` places that frame in the plane, so
"heavy end down" is ``yaw = -pi/2``.

Default part (length 2.2, width 0.7, heavy half 90% of the mass) and the feeder's default
friction (``feeders.feeder.DEFAULT_FRICTION``, mu = 0.05) come from a calibration, since the
paper gives neither (docs/calibration.md, ``partfeeder calibrate --part``): over a grid of
lengths, widths, mass splits and mu, this is the point where the geometric level reproduces all
eleven of the paper's feasibility verdicts and the paper's optimum ``table3`` orients the part
from both entries in the dynamic model (100 of 100 perturbed drops), with every neighbouring
grid point doing the same. The peg slides in the input chute (width ``a`` in [1.1, 1.2]) and
the exit chute (``b`` in [1.1, 1.3]) with 0.4-0.6 of play, and cannot turn round inside either,
because turning end for end in a strip needs the strip to be at least as wide as the peg is
long (2.2 > 1.3).

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


DEFAULT_LENGTH = 2.2
DEFAULT_WIDTH = 0.7
DEFAULT_HEAVY_FRACTION = 0.9


def two_density_moments(
    length: float, width: float, mass: float, heavy_fraction: float
) -> tuple[float, float]:
    """(centre-of-mass offset, inertia about the centre of mass) of a peg made of two uniform
    halves, the heavy one with ``heavy_fraction`` of ``mass`` (values assumed checked).

    Offset: (m_h - m_l)/m * L/4. Inertia: each half is a (L/2 x w) plate,
    I = m_i ((L/2)^2 + w^2)/12 about its centre, moved to the centre of mass.
    """
    m_h, m_l = heavy_fraction * mass, (1.0 - heavy_fraction) * mass
    offset = (m_h - m_l) / mass * length / 4.0
    own = ((length / 2.0) ** 2 + width**2) / 12.0
    inertia = (
        (m_h + m_l) * own + m_h * (length / 4 - offset) ** 2 + m_l * (length / 4 + offset) ** 2
    )
    return offset, inertia


_DEFAULT_OFFSET, _DEFAULT_INERTIA = two_density_moments(
    DEFAULT_LENGTH, DEFAULT_WIDTH, 1.0, DEFAULT_HEAVY_FRACTION
)


@dataclass(frozen=True)
class Peg:
    """A rectangular peg of ``length`` x ``width``, ``mass`` and a heavy end.

    ``com_offset`` is the distance from the geometric centre to the centre of mass, along the
    axis toward the heavy end; ``inertia`` is the moment of inertia about the centre of mass
    (mass * length^2).
    """

    length: float = DEFAULT_LENGTH
    width: float = DEFAULT_WIDTH
    mass: float = 1.0
    com_offset: float = _DEFAULT_OFFSET  # Peg.two_density() defaults
    inertia: float = _DEFAULT_INERTIA

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
        length: float = DEFAULT_LENGTH,
        width: float = DEFAULT_WIDTH,
        mass: float = 1.0,
        heavy_fraction: float = DEFAULT_HEAVY_FRACTION,
    ) -> Peg:
        """A peg made of two uniform halves; the heavy half has ``heavy_fraction`` of the mass
        (offset and inertia: :func:`two_density_moments`)."""
        _check("heavy_fraction", heavy_fraction, 0.5, 1.0)
        length = _check("length", length, *LENGTH_RANGE)
        width = _check("width", width, LENGTH_RANGE[0], length)
        mass = _check("mass", mass, *MASS_RANGE)
        offset, inertia = two_density_moments(length, width, mass, heavy_fraction)
        return cls(length=length, width=width, mass=mass, com_offset=offset, inertia=inertia)

    def body_vertices(self) -> np.ndarray:
        """Corners in the body frame (origin at the centre of mass), counter-clockwise, (4, 2)."""
        hx, hy, c = self.length / 2.0, self.width / 2.0, self.com_offset
        return np.array([[-hx - c, -hy], [hx - c, -hy], [hx - c, hy], [-hx - c, hy]])

    def bounding_radius(self) -> float:
        """Largest distance from the centre of mass to a corner."""
        return float(np.max(np.hypot(*self.body_vertices().T)))


DEFAULT_PEG = Peg.two_density()
