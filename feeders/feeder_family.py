"""The paper's 12-parameter feeder as one device family (issue 24).

A device family (:mod:`feeders.device_family`) is a parametric device read from YAML. The
paper's feeder is written in Python (:func:`feeders.feeder.build_feeder`: mitred walls, the
finger that holds pin B, the funnel, [feeder-geometry.md](../docs/feeder-geometry.md)), and
:class:`FeederFamily` gives it the same face: its 12 named parameters over Table 2's box, its
two entries, ``values``, ``build`` and ``made_bounds``. What takes a family takes it: the
verdict and the screen of :mod:`experiments.drop.family_verdict` give, trial for trial, the
feeder's own verdict and screen (tested), so the feeder's results stay what they are.

One difference from a YAML family: a made feeder's parameters are kept within what can be
built (``feeders.design.PHYSICAL_BOUNDS``, :meth:`FeederFamily.made_bounds`), as the verdict
has always made it; a YAML family's rules decide instead.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from feeders.design import (
    DESIGN_SPACE,
    PARAMETER_NAMES,
    PHYSICAL_BOUNDS,
    PRESETS,
    DesignParameters,
    DesignSpace,
)
from feeders.device_family import DeviceFamily, named_values
from feeders.feeder import DEFAULT_FRICTION, ORIENTATIONS, build_feeder
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import PEG_ORIENTATIONS, InputSet, OrientationClass, Scene

Vector = Mapping[str, float] | Sequence[float] | np.ndarray


@dataclass(frozen=True)
class FeederFamily:
    """The 12-parameter feeder as a device family: ``build`` is
    :func:`feeders.feeder.build_feeder` with this environment (part, friction, restitution,
    gravity, inputs); its box is Table 2's, its default the paper's optimum ``table3``, its
    entries heavy end leading and trailing."""

    name: str = "paper-feeder"
    part: Peg = DEFAULT_PEG
    friction: float = DEFAULT_FRICTION
    restitution: float = 0.3
    gravity: tuple[float, float] = (0.0, -9.81)
    inputs: InputSet = field(default_factory=InputSet)
    orientations: tuple[OrientationClass, ...] = PEG_ORIENTATIONS

    @property
    def vector_names(self) -> tuple[str, ...]:
        """The 12 parameters of Table 2, in the order of a vector."""
        return PARAMETER_NAMES

    @property
    def entries(self) -> tuple[tuple[str, None], ...]:
        """The entry orientations (a YAML family's pair is its name and pose expressions; the
        feeder's start poses follow from its design, :func:`build_feeder`)."""
        return tuple((o, None) for o in ORIENTATIONS)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)`` of Table 2's box, each shape (12,)."""
        return DESIGN_SPACE.low, DESIGN_SPACE.high

    def space(self) -> DesignSpace:
        """Table 2's box, as the feeder's sweep samples it."""
        return DESIGN_SPACE

    def default(self) -> np.ndarray:
        """The paper's optimum, table3 (Table 3)."""
        return PRESETS["table3"].to_vector()

    def values(self, vector: Vector) -> dict[str, float]:
        """``vector`` as a mapping of the 12 parameters (see
        :func:`feeders.device_family.named_values`)."""
        return named_values(self.name, PARAMETER_NAMES, vector)

    def made_bounds(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """``(low, high)`` a made feeder's parameters are kept within
        (``feeders.design.PHYSICAL_BOUNDS``: what can be built at all)."""
        return (
            tuple(PHYSICAL_BOUNDS[n][0] for n in PARAMETER_NAMES),
            tuple(PHYSICAL_BOUNDS[n][1] for n in PARAMETER_NAMES),
        )

    def build(self, vector: Vector) -> Scene:
        """The feeder of this design, or :class:`feeders.feeder.DegenerateDesign` with the
        reason."""
        design = DesignParameters.from_vector(list(self.values(vector).values()))
        return build_feeder(
            design,
            self.part,
            inputs=self.inputs,
            friction=self.friction,
            gravity=self.gravity,
            restitution=self.restitution,
        )


Family = DeviceFamily | FeederFamily
"""What takes a family takes either: a YAML family or the paper's feeder."""
