"""How a design's passive verdict is reached (:mod:`experiments.drop.verdict`): its target,
trial budget, step and perturbations. Apart from the verdict so that reading a config
(:mod:`experiments.sweep.config`) checks them without importing the dynamic level and numba
(issue 22: a bad config value waited 0.8 s for them)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from experiments.drop.perturbations import Perturbations

DYNAMIC_STEP = 1e-3  # h (s): validity.dynamic.DEFAULT_STEP (tests check they are equal)
WILSON = "wilson"  # decide on Wilson 95% intervals against the target at each look
SPRT = "sprt"  # decide by Wald's sequential probability ratio test, entry by entry
RULES = (WILSON, SPRT)
SPRT_KEYS = ("works_p", "fails_p", "error")  # what only the SPRT reads


@dataclass(frozen=True)
class VerdictSettings:
    """How a verdict is reached: the target probability, the trial budget (``min_drops``
    before the first look, then a look every ``batch``, at most ``max_drops``), the dynamic
    level's step h (s) and longest drop (s), and the perturbations.

    ``rule`` decides at each look: ``wilson`` (every entry's Wilson 95% interval on one
    side of ``target``) or ``sprt`` (Wald's sequential probability ratio test per entry
    between success probabilities ``works_p`` and ``fails_p``, each error rate ``error``:
    :mod:`experiments.drop.sequential`); ``target`` stays the bar the reports' intervals
    are read against."""

    target: float = 0.9
    min_drops: int = 10
    batch: int = 10
    max_drops: int = 200
    step: float = DYNAMIC_STEP
    t_max: float = 10.0
    perturbations: Perturbations = field(default_factory=Perturbations)
    rule: str = WILSON
    works_p: float = 0.95
    fails_p: float = 0.8
    error: float = 0.01

    def __post_init__(self) -> None:
        if self.rule not in RULES:
            raise ValueError(f"verdict.rule = {self.rule!r} is not one of {', '.join(RULES)}")
        checks = (
            ("target", self.target, 0.0, 1.0),
            ("min_drops", self.min_drops, 1, 100_000),
            ("batch", self.batch, 1, 100_000),
            ("max_drops", self.max_drops, 1, 100_000),
            ("step", self.step, 1e-6, 0.1),
            ("t_max", self.t_max, 1e-3, 3600.0),
            ("works_p", self.works_p, 0.001, 0.999),
            ("fails_p", self.fails_p, 0.001, 0.999),
            ("error", self.error, 1e-6, 0.25),
        )
        check_ranges("verdict", checks, whole=("min_drops", "batch", "max_drops"))
        if self.min_drops > self.max_drops:
            raise ValueError(
                f"verdict.min_drops = {self.min_drops} is more than max_drops = {self.max_drops}"
            )
        if self.fails_p >= self.works_p:
            raise ValueError(
                f"verdict.fails_p = {self.fails_p!r} must be below works_p = {self.works_p!r}"
            )

    def rule_fields(self) -> dict[str, object]:
        """The fields of the rule as a config holds them: ``rule`` and the SPRT's
        probabilities and error only when it is the rule (a Wilson config reads as it
        always has, so its results key does not change)."""
        if self.rule == WILSON:
            return {}
        return {"rule": self.rule, **{k: getattr(self, k) for k in SPRT_KEYS}}


def check_ranges(
    prefix: str, checks: tuple[tuple[str, object, float, float], ...], whole: tuple[str, ...]
) -> None:
    """ValueError naming ``prefix.name``, its value and the allowed range for the first of
    ``checks`` (name, value, low, high) that is not a finite number in [low, high] (a whole
    number for the names in ``whole``)."""
    for name, value, low, high in checks:
        if isinstance(value, bool) or not (isinstance(value, int | float) and math.isfinite(value)):
            raise ValueError(f"{prefix}.{name} = {value!r} must be a number")
        if name in whole and not isinstance(value, int):
            raise ValueError(f"{prefix}.{name} = {value!r} must be a whole number")
        if not low <= value <= high:
            raise ValueError(
                f"{prefix}.{name} = {value!r} is outside the allowed range [{low:g}, {high:g}]"
            )
