"""What a margin varies: the 12 design parameters over Table 2's box, the walls' Coulomb mu,
and the part's length, width and mass split, each over a stated range (the paper gives none:
they span the calibration's grid, docs/calibration.md, and what the feeder can hold).

The part is taken as two uniform halves (:meth:`feeders.part.Peg.two_density`); its mass split
(the heavy half's share of the mass, h) places the centre of mass (h - 1/2) L / 2 from the
middle, so varying it moves the off-centre mass.

A device family's design (:mod:`feeders.device_family`, issue 24) varies its own parameters,
each over the family's box (``family.bounds()``), and the walls' mu over the same stated
range; it has no part axes, whatever its part: a family's entry poses are expressions written
for its part (where its centre of mass starts in chute A), so a longer or wider part would
start where the family's own was placed, and the margin would measure that misplacement, not
the device's tolerance of the part. The part axes stay the 12-parameter feeder's, whose
entries follow the peg's dimensions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from feeders.design import PARAMETER_MEANINGS, PARAMETER_NAMES, TABLE2_BOUNDS

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

DESIGN = "design"  # a design parameter: the feeder's 12 or a device family's
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
TABLE2 = "Table 2"  # where an axis's box comes from
STATED = "stated range"
FAMILY_BOX = "the family's box"
FAMILY_UNIT = "-"  # a family's parameter: a length or an angle (rad), as its file writes it


@dataclass(frozen=True)
class Axis:
    """One thing a margin varies: its ``name``, ``kind`` (design, friction or part), the box
    the search stays within (``low``, ``high``), where that box comes from (``source``:
    Table 2, a stated range, a device family's box), its unit and meaning."""

    name: str
    kind: str
    low: float
    high: float
    source: str
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
        out.append(Axis(name, DESIGN, low, high, TABLE2, unit, PARAMETER_MEANINGS[name]))
    out.append(friction_axis())
    for name, (low, high) in PART_RANGES.items():
        unit = "share" if name == "heavy_fraction" else "length"
        out.append(Axis(name, PART, low, high, STATED, unit, PART_MEANINGS[name]))
    return tuple(out)


def friction_axis() -> Axis:
    """The walls' Coulomb mu over its stated range."""
    return Axis("mu", FRICTION, *FRICTION_RANGE, STATED, "-", "walls' Coulomb friction")


def family_axes(family: DeviceFamily) -> tuple[Axis, ...]:
    """Every axis of a device family's design, in order: its parameters, each over the
    family's box (``family.bounds()``), then mu; no part axes (see the module's note)."""
    meaning = f"parameter of {family.name}"
    out = [
        Axis(p.name, DESIGN, p.low, p.high, FAMILY_BOX, FAMILY_UNIT, meaning)
        for p in family.parameters
    ]
    out.append(friction_axis())
    return tuple(out)


AXIS_NAMES = tuple(a.name for a in axes())
