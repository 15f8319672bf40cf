"""The fidelity levels (one module each, one interface) and the kernels under them.

A level is built from a scene and offers ``is_valid(state)``, ``clearance(state)``,
``propagate(state, control, duration)``, ``control_bounds()`` and ``state_of_pose(pose)``,
with ``name``, ``state_dim`` and ``control_dim``. Choose one by name from ``LEVELS``.
"""

from __future__ import annotations

from validity.geometric import GeometricLevel

LEVELS = {"geometric": GeometricLevel}


def make_level(name: str, scene, **options):
    """The level called ``name`` on ``scene``; the error lists the levels there are."""
    try:
        cls = LEVELS[name]
    except KeyError:
        raise ValueError(f"unknown level '{name}'; levels: {', '.join(LEVELS)}") from None
    return cls(scene, **options)
