"""How a design's passive verdict is reached (:mod:`experiments.drop.verdict`): its target,
trial budget, step and perturbations. Apart from the verdict so that reading a config
(:mod:`experiments.sweep.config`) checks them without importing the dynamic level and numba
(issue 22: a bad config value waited 0.8 s for them)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from experiments.drop.perturbations import Perturbations

DYNAMIC_STEP = 1e-3  # h (s): validity.dynamic.DEFAULT_STEP (tests check they are equal)


@dataclass(frozen=True)
class VerdictSettings:
    """How a verdict is reached: the target probability, the trial budget (``min_drops``
    before the first look, then a look every ``batch``, at most ``max_drops``), the dynamic
    level's step h (s) and longest drop (s), and the perturbations."""

    target: float = 0.9
    min_drops: int = 10
    batch: int = 10
    max_drops: int = 200
    step: float = DYNAMIC_STEP
    t_max: float = 10.0
    perturbations: Perturbations = field(default_factory=Perturbations)

    def __post_init__(self) -> None:
        checks = (
            ("target", self.target, 0.0, 1.0),
            ("min_drops", self.min_drops, 1, 100_000),
            ("batch", self.batch, 1, 100_000),
            ("max_drops", self.max_drops, 1, 100_000),
            ("step", self.step, 1e-6, 0.1),
            ("t_max", self.t_max, 1e-3, 3600.0),
        )
        for name, value, low, high in checks:
            if isinstance(value, bool) or not (
                isinstance(value, int | float) and math.isfinite(value)
            ):
                raise ValueError(f"verdict.{name} = {value!r} must be a number")
            if name in ("min_drops", "batch", "max_drops") and not isinstance(value, int):
                raise ValueError(f"verdict.{name} = {value!r} must be a whole number")
            if not low <= value <= high:
                raise ValueError(
                    f"verdict.{name} = {value!r} is outside the allowed range [{low:g}, {high:g}]"
                )
        if self.min_drops > self.max_drops:
            raise ValueError(
                f"verdict.min_drops = {self.min_drops} is more than max_drops = {self.max_drops}"
            )
