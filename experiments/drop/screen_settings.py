"""How the screen (:mod:`experiments.drop.screen`) decides: its coarse step, the hypotheses
and error rates of its sequential test, and its budget. Apart from the screen so that reading
a config checks them without importing the dynamic level and numba (as
:mod:`experiments.drop.verdict_settings`)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from experiments.drop.perturbations import Perturbations
from experiments.drop.verdict_settings import check_ranges

SCREEN_STEP = 4e-3  # h (s): 4 x the verdict's; the same decision on 195 of 195 designs (docs)


@dataclass(frozen=True)
class ScreenSettings:
    """The screen's settings: the dynamic level's step h (s) and longest drop (s); Wald's
    test per entry between success probabilities ``works_p`` (the verdict's) and
    ``fails_p`` (below the verdict's 0.8: the screen fails only clear failures, three
    failed drops in a row at the least, and leaves marginal designs to the verdict), with
    ``false_fails`` the probability of calling a ``works_p`` entry failing (the screen's
    stated error: it prunes) and ``false_works`` of passing a ``fails_p`` one on to the
    verdict (it only costs time); at most ``max_drops`` drops per entry (then the screen has
    not decided, and the design goes on to the verdict); the perturbations of the verdict's
    drops."""

    step: float = SCREEN_STEP
    t_max: float = 10.0
    works_p: float = 0.95
    fails_p: float = 0.5
    false_fails: float = 0.001
    false_works: float = 0.1
    max_drops: int = 60
    perturbations: Perturbations = field(default_factory=Perturbations)

    def __post_init__(self) -> None:
        checks = (
            ("step", self.step, 1e-6, 0.1),
            ("t_max", self.t_max, 1e-3, 3600.0),
            ("works_p", self.works_p, 0.001, 0.999),
            ("fails_p", self.fails_p, 0.001, 0.999),
            ("false_fails", self.false_fails, 1e-9, 0.25),
            ("false_works", self.false_works, 1e-9, 0.5),
            ("max_drops", self.max_drops, 1, 100_000),
        )
        check_ranges("screen", checks, whole=("max_drops",))
        if self.fails_p >= self.works_p:
            raise ValueError(
                f"screen.fails_p = {self.fails_p!r} must be below works_p = {self.works_p!r}"
            )

    def fields(self) -> dict[str, float | int]:
        """The test's fields as a config holds them (the perturbations apart)."""
        out = asdict(self)
        out.pop("perturbations")
        return out
