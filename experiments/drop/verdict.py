"""The feeder's verdict: does the design orient the part, passively, with what probability.

A feeder is passive: the part slides in under gravity and must leave heavy end down whichever
way it entered (paper Section 4, Figs. 10-11). One nominal drop cannot say so: contact through
a feeder is chaotic (a 1e-9 change of the start changes the end), so the verdict is a success
probability over drops perturbed the way real ones are (:mod:`experiments.drop.perturbations`).

Each trial makes one feeder to tolerance, one friction coefficient, and drops the part once
from every entry orientation with its own entry noise. Per orientation the verdict reports
the success probability with a Wilson 95% interval; for the design the probability that one
trial succeeds from every entry ("P(both)"). The design *works* when the lower bound of every
orientation's interval clears ``target``. Trials run in batches and stop as soon as that is
decided either way (every lower bound above the target, or some upper bound below it), so a
clear case costs ``min_drops`` trials and only a marginal one runs to ``max_drops``; the
repeated looks make the intervals slightly optimistic at the stopping time, which is why the
decision needs the whole interval on one side. The ``sprt`` rule decides instead by Wald's
sequential test per entry (:mod:`experiments.drop.sequential`), which may look after every
trial and keeps its stated error rates. Every drop's outcome goes into the orientation
transition matrix (entry -> :data:`experiments.drop.outcomes.OUTCOMES`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from experiments.drop.outcomes import OUTCOMES, SIMULATION_FAULT, classify, outcome_classes
from experiments.drop.passive import passive_drop
from experiments.drop.perturbations import DropDraw, draw, toleranced
from experiments.drop.sequential import UNDECIDED, Wald, advance, design_decision
from experiments.drop.verdict_settings import SPRT, VerdictSettings
from experiments.proportions import wilson_interval
from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import DEFAULT_FRICTION, ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import Scene
from validity.dynamic import DynamicLevel

UNBUILDABLE = "feeder not buildable"  # the toleranced design has no valid feeder
CLASSES = (*OUTCOMES, UNBUILDABLE)
"""The feeder's transition matrix columns (success first); a scene with other orientation
classes has its own (:func:`classes_of`)."""
ENTRY_RETRIES = 6  # halvings of a drop's entry offset that puts the part into a wall


@dataclass(frozen=True)
class Trial:
    """One trial: per entry orientation, success, outcome class, T (s) and the distance
    ||q(T) - q_goal|| of Eq. 10 (both nan if unbuilt)."""

    index: int
    success: tuple[bool, ...]
    outcome: tuple[str, ...]
    T: tuple[float, ...]
    goal_error: tuple[float, ...] = ()

    @property
    def fault(self) -> bool:
        """A drop of the trial ended inside a wall: a failure of the simulation, not of the
        design; the verdict leaves the trial out and draws another."""
        return SIMULATION_FAULT in self.outcome


@dataclass(frozen=True)
class Verdict:
    """A design's verdict over its trials (plain data; :meth:`to_dict` for JSON)."""

    orientations: tuple[str, ...]
    trials: tuple[Trial, ...]
    target: float
    decision: str  # "works", "fails" or "undecided" (max_drops reached in between)
    wall_time: float
    classes: tuple[str, ...] = CLASSES  # the transition matrix's columns, success first
    success_classes: tuple[str, ...] = (OUTCOMES[0],)  # the goal's orientation classes

    @property
    def counted(self) -> tuple[Trial, ...]:
        """The trials the verdict counts: every one but the simulation faults."""
        return tuple(t for t in self.trials if not t.fault)

    @property
    def drops(self) -> int:
        return len(self.counted)

    @property
    def faults(self) -> int:
        """Trials left out because a drop ended inside a wall (:attr:`Trial.fault`)."""
        return len(self.trials) - self.drops

    def successes(self, orientation: str) -> int:
        k = self.orientations.index(orientation)
        return sum(t.success[k] for t in self.counted)

    def interval(self, orientation: str) -> tuple[float, float]:
        return wilson_interval(self.successes(orientation), self.drops)

    @property
    def both(self) -> int:
        return sum(all(t.success) for t in self.counted)

    @property
    def both_interval(self) -> tuple[float, float]:
        return wilson_interval(self.both, self.drops)

    @property
    def works(self) -> bool:
        return self.decision == "works"

    def transitions(self) -> dict[str, dict[str, int]]:
        """Entry orientation -> outcome class -> number of drops (every class of
        :attr:`classes` listed, then any other a drop ended in)."""
        seen = [c for t in self.trials for c in t.outcome]
        columns = [*self.classes, *dict.fromkeys(c for c in seen if c not in self.classes)]
        out = {o: dict.fromkeys(columns, 0) for o in self.orientations}
        for t in self.trials:
            for o, c in zip(self.orientations, t.outcome, strict=True):
                out[o][c] += 1
        return out

    def exit_times(self, orientation: str) -> list[float]:
        """T (s) of the successful drops from ``orientation``."""
        k = self.orientations.index(orientation)
        return [t.T[k] for t in self.counted if t.success[k]]

    def to_dict(self) -> dict:
        per = {}
        for o in self.orientations:
            lo, hi = self.interval(o)
            times = self.exit_times(o)
            per[o] = {
                "successes": self.successes(o),
                "p": self.successes(o) / max(self.drops, 1),
                "interval": [lo, hi],
                "mean_exit_time_s": sum(times) / len(times) if times else None,
            }
        lo, hi = self.both_interval
        return {
            "decision": self.decision,
            "works": self.works,
            "target": self.target,
            "drops": self.drops,
            "simulation_faults": self.faults,
            "orientations": per,
            "both": {
                "successes": self.both,
                "p": self.both / max(self.drops, 1),
                "interval": [lo, hi],
            },
            "transitions": self.transitions(),
            "success_classes": list(self.success_classes),
            "wall_time_s": self.wall_time,
        }


def entry_state(
    level: DynamicLevel, pose: Sequence[float], offset: Sequence[float], velocity: Sequence[float]
) -> tuple[float, ...]:
    """The perturbed entry state, the offset halved until the part is clear of every wall."""
    scale = 1.0
    for _ in range(ENTRY_RETRIES):
        state = (
            pose[0] + scale * offset[0],
            pose[1] + scale * offset[1],
            pose[2] + scale * offset[2],
            velocity[0],
            velocity[1],
            0.0,
        )
        if level.clearance(state) >= 0.0:
            return state
        scale *= 0.5
    return (pose[0], pose[1], pose[2], velocity[0], velocity[1], 0.0)


@dataclass(frozen=True)
class EntryDrop:
    """One perturbed drop from one entry: success, outcome class, T (s) and Eq. 10's
    distance to q_goal."""

    success: bool
    outcome: str
    T: float
    goal_error: float


def entry_drop(
    scene: Scene,
    level: DynamicLevel,
    orientation: str,
    perturbation: DropDraw,
    k: int,
    t_max: float,
) -> EntryDrop:
    """The drop from ``orientation`` (entry ``k`` of ``perturbation``) through the made
    ``scene`` with its dynamic ``level``, judged."""
    start = entry_state(
        level,
        scene.start(orientation),
        perturbation.entry_offsets[k],
        perturbation.entry_velocities[k],
    )
    result = passive_drop(scene, orientation, t_max=t_max, level=level, start=start)
    outcome = classify(scene, result.end, result.final_pose, result.success)
    return EntryDrop(result.success, outcome, result.T, result.goal_error)


def run_trial(
    make_scene: Callable[[DropDraw], Scene],
    orientations: Sequence[str],
    settings: VerdictSettings,
    seed: int,
    index: int,
    parameters: int = len(PARAMETER_NAMES),
) -> Trial:
    """Trial ``index`` of a verdict with ``seed``: one made feeder, a drop per orientation
    (``parameters``: how many design factors the draw makes; a device family's count)."""
    perturbation = draw(settings.perturbations, seed, index, len(orientations), parameters)
    try:
        scene = make_scene(perturbation)
    except DegenerateDesign:
        n = len(orientations)
        return Trial(index, (False,) * n, (UNBUILDABLE,) * n, (math.nan,) * n, (math.nan,) * n)
    level = DynamicLevel(scene, step=settings.step)
    success, outcome, times, errors = [], [], [], []
    for k, orientation in enumerate(orientations):
        drop = entry_drop(scene, level, orientation, perturbation, k, settings.t_max)
        success.append(drop.success)
        outcome.append(drop.outcome)
        times.append(drop.T)
        errors.append(drop.goal_error)
    return Trial(index, tuple(success), tuple(outcome), tuple(times), tuple(errors))


def looks(settings: VerdictSettings) -> list[int]:
    """The trial counts at which the verdict looks: ``min_drops``, then every ``batch`` more,
    and ``max_drops`` last."""
    out = [min(settings.min_drops, settings.max_drops)]
    while out[-1] < settings.max_drops:
        out.append(min(out[-1] + settings.batch, settings.max_drops))
    return out


def decide(successes: Sequence[int], drops: int, target: float) -> str:
    """ "works" when every orientation's Wilson lower bound clears ``target``, "fails" when
    some upper bound is below it, else "undecided"."""
    intervals = [wilson_interval(k, drops) for k in successes]
    if all(lo > target for lo, _ in intervals):
        return "works"
    if any(hi < target for _, hi in intervals):
        return "fails"
    return "undecided"


def verdict_of(
    make_scene: Callable[[DropDraw], Scene],
    orientations: Sequence[str],
    settings: VerdictSettings,
    seed: int,
    parameters: int = len(PARAMETER_NAMES),
) -> Verdict:
    """Trials of ``make_scene`` (a feeder made from a draw of ``parameters`` design factors)
    until the verdict is decided."""
    t0 = time.perf_counter()
    made: list[Scene] = []  # the first scene made: its classes name the matrix's columns

    def making(d: DropDraw) -> Scene:
        scene = make_scene(d)
        if not made:
            made.append(scene)
        return scene

    trials: list[Trial] = []
    counted: list[Trial] = []  # the trials without a simulation fault
    decision = UNDECIDED
    test = Wald(settings.works_p, settings.fails_p, settings.error)
    statuses = (UNDECIDED,) * len(orientations)  # the SPRT's per entry, final once decided
    for look in looks(settings):
        while len(counted) < look and len(trials) < look + settings.max_drops:
            trial = run_trial(making, orientations, settings, seed, len(trials), parameters)
            trials.append(trial)
            if not trial.fault:
                counted.append(trial)
        counts = [sum(t.success[k] for t in counted) for k in range(len(orientations))]
        if settings.rule == SPRT:
            statuses = advance(test, statuses, counts, len(counted))
            decision = design_decision(statuses)
        else:
            decision = decide(counts, len(counted), settings.target)
        if decision != UNDECIDED or len(counted) < look:
            break
    classes, success = classes_of(made[0]) if made else (CLASSES, (OUTCOMES[0],))
    return Verdict(
        tuple(orientations),
        tuple(trials),
        settings.target,
        decision,
        time.perf_counter() - t0,
        classes,
        success,
    )


def classes_of(scene: Scene) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The transition matrix's columns for drops through ``scene`` (its outcome classes, the
    goal's orientation classes first, then :data:`UNBUILDABLE`) and the goal's classes (the
    successes). For the feeder: :data:`CLASSES` and ("heavy end down",)."""
    return (*outcome_classes(scene), UNBUILDABLE), scene.goal.orientations


def design_verdict(
    design: DesignParameters,
    part: Peg = DEFAULT_PEG,
    friction: float | None = None,
    settings: VerdictSettings | None = None,
    seed: int = 0,
    **feeder_options,
) -> Verdict:
    """The verdict of a feeder design for ``part`` at ``friction`` (None: the feeder's
    default mu), both entries (:data:`feeders.feeder.ORIENTATIONS`); ``feeder_options`` go to
    :func:`feeders.feeder.build_feeder`."""
    settings = settings or VerdictSettings()
    make_scene = made_feeders(design, part, friction, **feeder_options)
    return verdict_of(make_scene, ORIENTATIONS, settings, seed)


def made_feeders(
    design: DesignParameters,
    part: Peg = DEFAULT_PEG,
    friction: float | None = None,
    **feeder_options,
) -> Callable[[DropDraw], Scene]:
    """The feeder of ``design`` as made for one trial's draw (toleranced parameters, the
    part batch's friction), for :func:`run_trial`. Raises
    :class:`feeders.feeder.DegenerateDesign` at once if the nominal design cannot be built."""
    build_feeder(design, part, **feeder_options)
    options = dict(feeder_options)
    mu = DEFAULT_FRICTION if friction is None else friction

    def make_scene(d: DropDraw) -> Scene:
        made = toleranced(design, d.design_factors)
        return build_feeder(made, part, friction=mu * d.friction_factor, **options)

    return make_scene


def scene_verdict(scene: Scene, settings: VerdictSettings | None = None, seed: int = 0) -> Verdict:
    """The verdict of a scene as it is (free-form or built): entry and friction perturbed,
    the obstacles not (a scene has no design to make to tolerance); every start it has."""
    settings = settings or VerdictSettings()

    def make_scene(d: DropDraw) -> Scene:
        return dataclasses.replace(scene, friction=scene.friction * d.friction_factor)

    return verdict_of(make_scene, tuple(scene.starts), settings, seed)
