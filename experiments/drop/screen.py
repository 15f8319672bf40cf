"""The screen: a cheap first look at a design's verdict that can only fail it (issues 21, 36).

Most designs fail (94% of the first 1,000 Halton designs), and the verdict
(:mod:`experiments.drop.verdict`) spends most of its time proving it. The screen is the
verdict's procedure made cheaper in three ways, each measured in docs/verdict.md:

- a coarser step (``h = 4e-3``, four times the verdict's). On paired draws it lowers an
  entry's success probability in a few designs (by 0.06 to 0.11 in designs 181 and 214 of the
  first 1,000), so the screen's test states its error for the verdict's p with that shift
  folded into its hypotheses (:class:`experiments.drop.screen_settings.ScreenSettings`), or,
  with ``confirm_step``, confirms a failure on the same draws at the verdict's step
  (:func:`run_sequence`: then for any coupling of the two steps);
- Wald's test per entry (:mod:`experiments.drop.sequential`) with a small error where it
  matters: calling an entry that works at ``works_p`` failing has probability at most about
  ``false_fails`` (0.001), while passing a ``fails_p`` entry on to the verdict is allowed
  (``false_works``, 0.01), since it costs only the verdict's time;
- one drop per made feeder, from the entry most likely to fail so far (the lowest
  log-likelihood ratio; ``first_entry`` on a tie), so a design that fails from one entry is
  decided by that entry's drops alone: four failures in a row, not four trials of both.

The design *fails* the screen as soon as one entry fails its test, *passes* when every entry
passes, and is *undecided* when an entry is still undecided after ``max_drops`` drops of its
own; only a failure prunes. A drop's draw is :func:`experiments.drop.perturbations.draw` of
the screen's seed and the drop's index, so the same seed gives the same screen on any
executor. The screen's decisions depend only on the outcomes of the drops it sees, which is
what lets :mod:`experiments.drop.resampled` replay it against a pool of simulated drops. The
exact operating characteristic: :func:`experiments.drop.operating.screen_operating_point`
and :func:`experiments.drop.operating.screen_fails_at_verdict_p`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial

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
    fine_drops: int = 0  # drops run at the confirmation step (the verdict's)

    @property
    def total_drops(self) -> int:
        """The coarse drops: counted and faults (the fine ones are :attr:`fine_drops`)."""
        return sum(self.drops) + self.faults

    def to_dict(self) -> dict:
        return {
            "decision": self.decision,
            "drops": self.total_drops,
            "simulation_faults": self.faults,
            "fine_drops": self.fine_drops,
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
    first: int = 0,
) -> int | None:
    """The undecided entry most likely to fail so far (the lowest log-likelihood ratio; on a
    tie, entry ``first``, then those after it in turn) among those with fewer than
    ``max_drops`` drops; None when there is none."""
    n = len(statuses)
    open_ = [
        k
        for k, s in enumerate(statuses)
        if s == UNDECIDED and (max_drops is None or drops[k] < max_drops)
    ]
    if not open_:
        return None
    return min(open_, key=lambda k: (test.llr(successes[k], drops[k]), (k - first) % n))


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

    def at(step: float) -> Callable[[int, int], bool | None]:
        def drop(k: int, index: int) -> bool | None:
            perturbation = draw(settings.perturbations, seed, index, n, parameters)
            try:
                scene = make_scene(perturbation)
            except DegenerateDesign:
                return False
            level = DynamicLevel(scene, step=step)
            result = entry_drop(scene, level, orientations[k], perturbation, k, settings.t_max)
            return None if result.outcome == SIMULATION_FAULT else result.success

        return drop

    confirm = None if settings.confirm_step is None else at(settings.confirm_step)
    run = run_sequence(
        wald_of(settings), n, settings.max_drops, at(settings.step), confirm, settings.first_entry
    )
    return Screen(
        tuple(orientations),
        run.drops,
        run.successes,
        run.statuses,
        screen_decision(run.statuses),
        run.faults,
        time.perf_counter() - t0,
        run.fine_drops,
    )


def sequence(
    test: Wald,
    entries: int,
    max_drops: int,
    drop: Callable[[int, int], bool | None],
    confirm: Callable[[int, int], bool | None] | None = None,
    first_entry: int = 0,
) -> tuple[tuple[str, ...], tuple[int, ...], tuple[int, ...], int]:
    """:func:`run_sequence`'s statuses, successes, drops and faults (per entry, then the
    faults of the coarse drops)."""
    run = run_sequence(test, entries, max_drops, drop, confirm, first_entry)
    return run.statuses, run.successes, run.drops, run.faults


@dataclass(frozen=True)
class ScreenRun:
    """The screen's loop's end: per entry the test's status, successes and drops (at the
    step the entry's test ended on), the coarse drops left out as faults, the drops run at the
    confirmation step (``fine_drops``), which entries went on at that step (``fine``) and the
    drops run at the screen's step (``coarse_drops``)."""

    statuses: tuple[str, ...]
    successes: tuple[int, ...]
    drops: tuple[int, ...]
    faults: int
    fine_drops: int = 0
    fine: tuple[bool, ...] = ()
    coarse_drops: int = 0  # every drop run at the screen's step, faults included


def run_sequence(
    test: Wald,
    entries: int,
    max_drops: int,
    drop: Callable[[int, int], bool | None],
    confirm: Callable[[int, int], bool | None] | None = None,
    first_entry: int = 0,
) -> ScreenRun:
    """The screen's loop: ``drop(k, index)`` (success, or None for a fault, which is not
    counted) from entry :func:`next_entry`, the draw ``index`` counting up from 0, until
    :func:`screen_decision` decides, every undecided entry has had ``max_drops`` drops (each
    entry's test is truncated at ``max_drops`` of its own, as the operating characteristic
    assumes), or ``max_drops`` faults have come. The first drop is from ``first_entry`` (an
    index; -1 the last), as is the next on any tie.

    With ``confirm`` (the same draw's drop at the verdict's step, issue 36), an entry whose
    coarse test fails is failed only when the same draws at the fine step fail the test too
    (:func:`confirmed`); else it goes on with every later drop at the fine step, its test
    restarted on the fine outcomes of all its draws. So an entry is failed only when its
    fine-step log-likelihood ratio, over a prefix of its own draws, is at or below the
    test's lower bound: the fine-step walk crossed it. Whatever the coarse step does, that
    has probability at most ``false_fails / (1 - false_works)`` for an entry whose fine-step
    p is ``works_p`` (Ville's inequality for the likelihood-ratio martingale) and is exactly
    :func:`experiments.drop.operating.crossing_probability` at any p: the stated error
    holds at the verdict's step, for any coupling of the two steps' outcomes."""
    statuses, successes, drops = [UNDECIDED] * entries, [0] * entries, [0] * entries
    history: list[list[tuple[int, bool]]] = [[] for _ in range(entries)]  # (index, coarse)
    fine = [False] * entries
    faults = index = fine_drops = coarse_drops = 0
    while screen_decision(statuses) == UNDECIDED:
        k = next_entry(test, statuses, successes, drops, max_drops, first_entry % entries)
        if k is None:
            break
        if fine[k]:
            assert confirm is not None
            success = confirm(k, index)
            fine_drops += 1
        else:
            success = drop(k, index)
            coarse_drops += 1
        index += 1
        if success is None:
            faults += 1
            if faults >= max_drops:
                break
            continue
        history[k].append((index - 1, success))
        drops[k] += 1
        successes[k] += success
        statuses[k] = test.status(successes[k], drops[k])
        if statuses[k] == FAILS and confirm is not None and not fine[k]:
            verdict, outcomes = confirmed(test, history[k], partial(confirm, k))
            fine_drops += len(outcomes)
            if not verdict:
                # go on at the fine step: the entry's test restarts on every draw's fine
                # outcome (a draw that faults at the fine step is left out)
                fine[k] = True
                counted = [v for v in outcomes.values() if v is not None]
                successes[k], drops[k] = sum(counted), len(counted)
                statuses[k] = test.status(successes[k], drops[k])
    return ScreenRun(
        tuple(statuses),
        tuple(successes),
        tuple(drops),
        faults,
        fine_drops,
        tuple(fine),
        coarse_drops,
    )


def confirmed(
    test: Wald,
    history: Sequence[tuple[int, bool]],
    confirm: Callable[[int], bool | None],
) -> tuple[bool, dict[int, bool | None]]:
    """Whether an entry whose coarse drops ``history`` ((draw index, success), in order)
    failed the test fails it on the same draws at the fine step (``confirm(index)``), and
    the fine outcomes run. The coarse failures are replayed first (newest first), then the
    successes; the replay stops as soon as the answer is known: yes when the fine
    log-likelihood ratio with every draw not yet replayed counted a success is at or below
    the lower bound (the true one is lower still), no when it is above it with every such
    draw counted a failure (then every draw is replayed, so that the entry can go on at the
    fine step). A draw that faults at the fine step is left out of the count."""
    order = [i for i, s in reversed(history) if not s] + [i for i, s in reversed(history) if s]
    outcomes: dict[int, bool | None] = {}
    won = lost = 0
    undecidable = False
    for i in order:
        result = confirm(i)
        outcomes[i] = result
        if result is not None:
            won += result
            lost += not result
        unknown = len(history) - len(outcomes)
        if not undecidable:
            best = test.llr(won + unknown, won + lost + unknown)  # the rest succeed
            if best <= test.lower:
                return True, outcomes
            worst = test.llr(won, won + lost + unknown)  # the rest fail
            undecidable = worst > test.lower
    return False, outcomes


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
