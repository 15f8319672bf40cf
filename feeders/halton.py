"""Scrambled, seeded Halton samples of the design space (paper Section 3, ref. [24])."""

from __future__ import annotations

import numpy as np
from scipy.stats import qmc

from feeders.design import DESIGN_SPACE, DesignParameters, DesignSpace


def halton_points(n: int, seed: int, space: DesignSpace = DESIGN_SPACE) -> np.ndarray:
    """``n`` points of the box, shape (n, 12): a scrambled Halton sequence seeded by ``seed``.

    The same ``(n, seed)`` always gives the same points; the first ``m`` of ``n`` points are the
    points of ``n = m`` (a prefix), so a sweep can grow without re-running what it has.
    """
    if n < 0:
        raise ValueError(f"number of designs n = {n} must be >= 0")
    sampler = qmc.Halton(d=len(space.bounds), scramble=True, seed=np.random.default_rng(seed))
    return space.scale(sampler.random(n))


def halton_designs(n: int, seed: int, space: DesignSpace = DESIGN_SPACE) -> list[DesignParameters]:
    """:func:`halton_points` as design values."""
    return [DesignParameters.from_vector(row) for row in halton_points(n, seed, space)]
