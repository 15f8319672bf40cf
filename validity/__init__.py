"""The fidelity levels (one module each, one interface) and the kernels under them.

Every level is built from a scene and keeps the contract of :class:`validity.level.Level`.
Choose one by name from ``LEVELS``.
"""

from __future__ import annotations

from validity.dynamic import DynamicLevel
from validity.geometric import GeometricLevel
from validity.kinematic import KinematicLevel

LEVELS = {"geometric": GeometricLevel, "kinematic": KinematicLevel, "dynamic": DynamicLevel}


def make_level(name: str, scene, **options):
    """The level called ``name`` on ``scene``; the error lists the levels there are."""
    try:
        cls = LEVELS[name]
    except KeyError:
        raise ValueError(f"unknown level '{name}'; levels: {', '.join(LEVELS)}") from None
    return cls(scene, **options)
