"""What a margin varies: the 12 design parameters over Table 2's box, the walls' Coulomb mu,
and the part's length, width and mass split, each over a stated range (the paper gives none:
they span the calibration's grid, docs/calibration.md, and what the feeder can hold).

The part is taken as two uniform halves (:meth:`feeders.part.Peg.two_density`); its mass split
(the heavy half's share of the mass, h) places the centre of mass (h - 1/2) L / 2 from the
middle, so varying it moves the off-centre mass.
"""

from __future__ import annotations

from dataclasses import dataclass

from feeders.design import PARAMETER_MEANINGS, PARAMETER_NAMES, TABLE2_BOUNDS

DESIGN = "design"
FRICTION = "friction"
PART = "part"

FRICTION_RANGE = (0.0, 0.3)  # mu: frictionless to the calibration grid's highest (0.3)
PART_RANGES: dict[str, tuple[float, float]] = {
    "length": (1.6, 2.8),  # the calibration grid's shortest; about two input chutes' width
    "width": (0.4, 1.0),  # below the narrowest chute in Table 2 (a, b >= 1.1)
    "heavy_fraction": (0.5, 1.0),  # no offset to all the mass in the heavy half
}
PART_MEANINGS = {
    "length": "length of the peg",
    "width": "width of the peg",
    "heavy_fraction": "heavy half's share of the mass (off-centre mass)",
}
ANGLES = ("theta", "alpha")


@dataclass(frozen=True)
class Axis:
    """One thing a margin varies: its ``name``, ``kind`` (design, friction or part), the box
    the search stays within (``low``, ``high``), whether that box is Table 2's, its unit and
    meaning."""

    name: str
    kind: str
    low: float
    high: float
    table2: bool
    unit: str
    meaning: str

    @property
    def width(self) -> float:
        return self.high - self.low


def axes() -> tuple[Axis, ...]:
    """Every axis, in order: the 12 design parameters (Table 2), mu, then the part."""
    out = []
    for name in PARAMETER_NAMES:
        low, high = TABLE2_BOUNDS[name]
        unit = "rad" if name in ANGLES else "length"
        out.append(Axis(name, DESIGN, low, high, True, unit, PARAMETER_MEANINGS[name]))
    out.append(Axis("mu", FRICTION, *FRICTION_RANGE, False, "-", "walls' Coulomb friction"))
    for name, (low, high) in PART_RANGES.items():
        unit = "share" if name == "heavy_fraction" else "length"
        out.append(Axis(name, PART, low, high, False, unit, PART_MEANINGS[name]))
    return tuple(out)


AXIS_NAMES = tuple(a.name for a in axes())
