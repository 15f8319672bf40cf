"""The screen: a cheap first look at a design's verdict that can only fail it (issue 21).

Most designs fail (94% of the first 1,000 Halton designs), and the verdict
(:mod:`experiments.drop.verdict`) spends most of its time proving it. The screen is the
verdict's procedure made cheaper in three ways, each measured in docs/verdict.md:

- a coarser step (``h = 4e-3``, four times the verdict's): the dynamic model's decision was
  the same at ``h = 1e-3`` and ``4e-3`` on all 195 buildable designs of the first 200;
- Wald's test per entry (:mod:`experiments.drop.sequential`) with a small error where it
  matters: calling an entry that works at ``works_p`` failing has probability at most about
  ``false_fails`` (0.001), while passing a ``fails_p`` entry on to the verdict is allowed
  often (``false_works``, 0.1), since it costs only the verdict's time;
- one drop per made feeder, from the entry most likely to fail so far (the lowest
  log-likelihood ratio; the first entry on a tie), so a design that fails from one entry is
  decided by that entry's drops alone: five failures in a row, not five trials of both.

The design *fails* the screen as soon as one entry fails its test, *passes* when every entry
passes, and is *undecided* when an entry is still undecided after ``max_drops`` drops of its
own; only a failure prunes. A
drop's draw is :func:`experiments.drop.perturbations.draw` of the screen's seed and the drop's
index, so the same seed gives the same screen on any executor. The exact operating
characteristic: :func:`experiments.drop.operating.screen_operating_point`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from experiments.drop.outcomes import SIMULATION_FAULT
from experiments.drop.perturbations import DropDraw, draw
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.sequential import FAILS, UNDECIDED, WORKS, Wald
from experiments.drop.verdict import entry_drop, made_feeders
from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import Scene
from validity.dynamic import DynamicLevel

PASSES = "passes"  # every entry passed its test: the design goes on to the verdict


@dataclass(frozen=True)
class Screen:
    """A design's screen (plain data; :meth:`to_dict` for JSON): per entry the drops counted,
    their successes and the test's status; the design's decision (``fails``, ``passes`` or
    ``undecided``); drops left out as simulation faults; wall time (s)."""

    orientations: tuple[str, ...]
    drops: tuple[int, ...]
    successes: tuple[int, ...]
    statuses: tuple[str, ...]
    decision: str
    faults: int
    wall_time: float

    @property
    def total_drops(self) -> int:
        return sum(self.drops) + self.faults

    def to_dict(self) -> dict:
        return {
            "decision": self.decision,
            "drops": self.total_drops,
            "simulation_faults": self.faults,
            "orientations": {
                o: {"drops": n, "successes": k, "status": s}
                for o, n, k, s in zip(
                    self.orientations, self.drops, self.successes, self.statuses, strict=True
                )
            },
            "wall_time_s": self.wall_time,
        }


def wald_of(settings: ScreenSettings) -> Wald:
    """The screen's sequential test of one entry."""
    return Wald(
        settings.works_p,
        settings.fails_p,
        false_works=settings.false_works,
        false_fails=settings.false_fails,
    )


def next_entry(
    test: Wald,
    statuses: Sequence[str],
    successes: Sequence[int],
    drops: Sequence[int],
    max_drops: int | None = None,
) -> int | None:
    """The undecided entry most likely to fail so far (the lowest log-likelihood ratio, the
    first on a tie) among those with fewer than ``max_drops`` drops; None when there is
    none."""
    open_ = [
        k
        for k, s in enumerate(statuses)
        if s == UNDECIDED and (max_drops is None or drops[k] < max_drops)
    ]
    if not open_:
        return None
    return min(open_, key=lambda k: (test.llr(successes[k], drops[k]), k))


def screen_decision(statuses: Sequence[str]) -> str:
    """``fails`` as soon as an entry fails, ``passes`` when all pass, else ``undecided``."""
    if FAILS in statuses:
        return FAILS
    if all(s == WORKS for s in statuses):
        return PASSES
    return UNDECIDED


def screen_of(
    make_scene: Callable[[DropDraw], Scene],
    orientations: Sequence[str],
    settings: ScreenSettings,
    seed: int,
    parameters: int = len(PARAMETER_NAMES),
) -> Screen:
    """Drops of ``make_scene`` (a feeder made from a draw), one entry at a time, until the
    screen decides (:func:`sequence`). A made feeder that cannot be built counts as a failed
    drop (as in the verdict); a drop that ends inside a wall is a fault of the simulation
    and is drawn again. ``parameters``: how many design factors a draw makes (a device
    family's count)."""
    t0 = time.perf_counter()
    n = len(orientations)

    def drop(k: int, index: int) -> bool | None:
        perturbation = draw(settings.perturbations, seed, index, n, parameters)
        try:
            scene = make_scene(perturbation)
        except DegenerateDesign:
            return False
        level = DynamicLevel(scene, step=settings.step)
        result = entry_drop(scene, level, orientations[k], perturbation, k, settings.t_max)
        return None if result.outcome == SIMULATION_FAULT else result.success

    statuses, successes, drops, faults = sequence(wald_of(settings), n, settings.max_drops, drop)
    return Screen(
        tuple(orientations),
        drops,
        successes,
        statuses,
        screen_decision(statuses),
        faults,
        time.perf_counter() - t0,
    )


def sequence(
    test: Wald, entries: int, max_drops: int, drop: Callable[[int, int], bool | None]
) -> tuple[tuple[str, ...], tuple[int, ...], tuple[int, ...], int]:
    """The screen's loop: ``drop(k, index)`` (success, or None for a fault, which is not
    counted) from entry :func:`next_entry`, the draw ``index`` counting up from 0, until
    :func:`screen_decision` decides, every undecided entry has had ``max_drops`` drops (each
    entry's test is truncated at ``max_drops`` of its own, as the operating characteristic
    assumes), or ``max_drops`` faults have come. Returns per entry the statuses, successes
    and drops, and the faults."""
    statuses, successes, drops = [UNDECIDED] * entries, [0] * entries, [0] * entries
    faults = index = 0
    while screen_decision(statuses) == UNDECIDED:
        k = next_entry(test, statuses, successes, drops, max_drops)
        if k is None:
            break
        success = drop(k, index)
        index += 1
        if success is None:
            faults += 1
            if faults >= max_drops:
                break
            continue
        drops[k] += 1
        successes[k] += success
        statuses[k] = test.status(successes[k], drops[k])
    return tuple(statuses), tuple(successes), tuple(drops), faults


def design_screen(
    design: DesignParameters,
    part: Peg = DEFAULT_PEG,
    friction: float | None = None,
    settings: ScreenSettings | None = None,
    seed: int = 0,
    **feeder_options,
) -> Screen:
    """The screen of a feeder design, both entries, feeders made as the verdict makes them
    (:func:`experiments.drop.verdict.made_feeders`; it raises
    :class:`feeders.feeder.DegenerateDesign` if the nominal design cannot be built).

    >>> from feeders.design import PRESETS
    >>> design_screen(PRESETS["fig5b"], seed=1).decision
    'fails'
    """
    make_scene = made_feeders(design, part, friction, **feeder_options)
    return screen_of(make_scene, ORIENTATIONS, settings or ScreenSettings(), seed)
